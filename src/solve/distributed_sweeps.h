#pragma once
// The iterative solvers' sweeps over MPI ranks (core/distributed.h): rank r updates the rows of its block of F
// (contiguous, about equal non-zeros each), then the ranks exchange their rows of B (allgather) and take the
// largest residual, once per sweep. Jacobi is then the same iteration as on one process (bit-identical); Gauss-
// Seidel becomes block Gauss-Seidel within a rank and Jacobi between ranks (gauss_seidel.h; its rate in
// docs/scaling.md, "Over MPI"). With one process the block is every row and the exchange does nothing.
#include <vector>

#include "core/distributed.h"
#include "core/types.h"
#include "formfactor/sparse_f.h"

namespace radwalk {

// The row blocks of every rank for F (rank r sweeps rows [blocks[r].begin, blocks[r].end)). Not collective.
std::vector<distributed::Range> sweep_row_blocks(const SparseF& F);

// Collective: every rank updated the rows of its own block of B; afterwards every rank has all rows.
void exchange_rows(PatchRgb& B, const std::vector<distributed::Range>& blocks);

}  // namespace radwalk
