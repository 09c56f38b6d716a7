#pragma once
// The iterative solvers' sweeps over MPI ranks (core/distributed.h): rank r updates the rows of its block of F
// (contiguous, about equal non-zeros each), then the ranks exchange their rows of B (allgather) and take the
// largest residual, once per sweep. Jacobi is then the same iteration as on one process (bit-identical); Gauss-
// Seidel becomes block Gauss-Seidel within a rank and Jacobi between ranks (gauss_seidel.h; its rate in
// docs/scaling.md, "Over MPI"). When F is row-distributed (problem.h, row_blocks) each rank holds only the rows
// it sweeps. With one process the block is every row and the exchange does nothing.
#include <vector>

#include "core/distributed.h"
#include "core/types.h"
#include "formfactor/sparse_f.h"
#include "solve/problem.h"

namespace radwalk {

// The row blocks of every rank for p (rank r sweeps rows [blocks[r].begin, blocks[r].end)): p.row_blocks when
// F is row-distributed (each rank holds the rows it sweeps), else blocks of about equal non-zeros of F. Not
// collective.
std::vector<distributed::Range> sweep_row_blocks(const RadiosityProblem& p);

// Collective: every rank updated the rows of its own block of B; afterwards every rank has all rows.
void exchange_rows(PatchRgb& B, const std::vector<distributed::Range>& blocks);
void exchange_rows(Eigen::VectorXd& x, const std::vector<distributed::Range>& blocks);

}  // namespace radwalk
