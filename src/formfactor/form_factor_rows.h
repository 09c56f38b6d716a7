#pragma once
// The rows of F over the ranks of an MPI run (core/distributed.h; docs/scaling.md, "Over MPI").
//
// Over R > 1 ranks F is row-distributed: one partition of its rows into contiguous blocks, RowBlocks (block r =
// rows [blocks[r].begin, blocks[r].end) of rank r), known to every rank, and on each rank an N x N CSR SparseF
// whose other rows are empty (an O(N) outer index plus the non-zeros of its own rows). The blocks are balanced by
// rays when F is estimated (form_factors.h), by non-zeros when it is read (form_factor_file.h). Empty RowBlocks
// mean that every rank holds every row (one process, or F gathered whole). Row i of a row-distributed F is, on
// the rank that holds it, the same bits as row i of the F one process has.
//
// The stages that sweep rows (Jacobi, Gauss-Seidel, the residual, the spectral radius: solve/) work on the rows
// alone; a stage that needs the whole F (entries F_ji of other rows, a transpose, a factorisation, a walk) calls
// gather_whole_rows, and says so.
#include <cstdint>
#include <vector>

#include "core/distributed.h"
#include "formfactor/sparse_f.h"

namespace radwalk {

using RowBlocks = std::vector<distributed::Range>;

// True when F on this rank holds only the rows of its own block (R > 1 and blocks given).
inline bool holds_own_rows_only(const RowBlocks& blocks) { return !blocks.empty() && distributed::size() > 1; }

// The rows this rank holds: its block, or every row [0, n) when every rank holds all.
distributed::Range own_rows(const RowBlocks& blocks, std::size_t n);

// Contiguous row blocks for this run's ranks with about equal sweep cost each, the weight of row i being
// 1 + its non-zeros (outer: a CSR outer index of n + 1 entries). Not collective.
RowBlocks nonzero_row_blocks(const std::int32_t* outer, std::size_t n);

// A compressed copy of F with only the rows in `keep` (the others empty). Not collective.
SparseF keep_rows(const SparseF& F, distributed::Range keep);

// Collective: afterwards every rank's F holds every row (each row's entries from the rank that held it, so F is
// bit for bit the one a single process has) and blocks is empty. Nothing to do when F is already whole. The one
// way a stage gets the whole F over MPI (counted: whole_row_gathers).
void gather_whole_rows(SparseF& F, RowBlocks& blocks);

// How many times gather_whole_rows gathered rows in this process (0 on the row-distributed path; the JSON
// summary's mpi.whole_form_factor_gathers).
long whole_row_gathers();

// Collective: the whole F for rank 0's own use (writing the file, the diagnostics that need F_ji), after which it
// is dropped. When every rank holds every row (blocks empty), F itself; otherwise `gathered`, filled on rank 0
// with the whole F (rank 0's rows, then every other rank's in rank order, received straight into its arrays; F
// must be compressed) and on the other ranks an empty N x N matrix. Rank 0 holds the whole F while it is used;
// the other ranks send their rows from F's arrays without a copy.
const SparseF& gather_rows_to_root(const SparseF& F, const RowBlocks& blocks, SparseF& gathered);

// Collective: the non-zeros of F summed over the ranks' own rows (F.nonZeros() when every rank holds all).
std::uint64_t total_nonzeros(const SparseF& F, const RowBlocks& blocks);

// Collective: every rank's stored non-zeros of F (F.nonZeros()), in rank order.
std::vector<std::uint64_t> nonzeros_by_rank(const SparseF& F);

}  // namespace radwalk
