#pragma once
// GMRES for a block of right-hand sides, X = Z + H X (H = diag(rho) F; column 3k + c of Z and X belongs to channel
// c, as in block_jacobi.h): one restarted GMRES(kBlockGmresRestart) per column, right-preconditioned by a forward
// Gauss-Seidel sweep (solve/gmres.h), all columns in lockstep so that each iteration is one pass over F for every
// column at once (the cost of one block Jacobi sweep). For systems whose spectral radius is close to 1 (the
// re-radiating rows, rho = 1, of the net-radiation system), where block Jacobi needs ~1 / (1 - radius) sweeps.
// Stops when every column's exact residual ||Z_k - (I - H) X_k||_inf is at most `tolerance` times ||Z_k||_inf
// (checked after each restart cycle). Needs every row of F (not row-distributed). Sequential.
#include "solve/block_jacobi.h"

namespace radwalk {

inline constexpr int kBlockGmresRestart = 20;

// Z: N x 3K. Throws InputError naming `what` when the columns do not converge within 10,000 iterations or stagnate.
BlockSolution solve_block_gmres(const RadiosityProblem& p, const RowBlock& Z, double tolerance, const char* what);

}  // namespace radwalk
