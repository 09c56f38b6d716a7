#pragma once
// Gauss-Seidel iteration for (I - H_c) B_c = E_c, H_c = diag(rho_c) F, all three channels per sweep, in patch
// order (walks F row by row, as stored):
//   B_i <- (E_i + rho_i sum_{j != i} F_ij B_j) / D_i,   D_i = 1 - rho_i F_ii,   B^0 = E / D,
// with B_j already updated for j < i. With A = I - H = D - L - U (L, U the strict triangles of H), the residual of
// the previous iterate is r(B^k) = (D - L)(B^{k+1} - B^k); its row i, D_i dB_i - rho_i sum_{j<i} F_ij dB_j, is
// accumulated during the sweep from the same row of F, so every sweep measures the exact relative residual of
// B^k. Stops when it is <= tol and returns B^{k+1} with its own residual computed exactly.
// For H >= 0 with radius(H) < 1 it converges at least as fast as Jacobi (Stein-Rosenberg); checked before
// iterating and watched while iterating (convergence.h). Sequential. iterations = sweeps.
// Over MPI (distributed_sweeps.h) rank r sweeps its block of rows [a_r, b_r) so, with B_j of the previous sweep
// for j outside the block, and the ranks exchange their rows after each sweep: block Gauss-Seidel within a rank,
// Jacobi between ranks (the lower sums above run over a_r <= j < i, which keeps the residual exact for that
// splitting). Its rate lies between Jacobi's and Gauss-Seidel's (docs/scaling.md, "Over MPI").
#include "solve/problem.h"
#include "core/solution.h"
#include "solve/solve_options.h"

namespace radwalk {

// Throws InputError for a bad problem or options.
Solution solve_gauss_seidel(const RadiosityProblem& p, const SolveOptions& options = {});

}  // namespace radwalk
