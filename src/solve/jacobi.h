#pragma once
// Jacobi iteration for (I - H_c) B_c = E_c, H_c = diag(rho_c) F, all three channels per sweep:
//   B^{k+1}_i = (E_i + rho_i sum_{j != i} F_ij B^k_j) / D_i,   D_i = 1 - rho_i F_ii,   B^0 = E / D.
// Every patch uses the previous sweep only, so rows run in parallel. The update is the residual of the previous
// iterate, r(B^k) = D (B^{k+1} - B^k), so each sweep measures the exact relative residual (residual.h) of B^k for
// free; the solve stops when it is <= tol and returns B^{k+1} with its own residual computed exactly.
// Converges iff the spectral radius of D^{-1}(H - diag H) is < 1 (implied by radius(H) < 1, H >= 0); checked
// before iterating and watched while iterating (convergence.h). iterations = sweeps.
#include "solve/problem.h"
#include "core/solution.h"
#include "solve/solve_options.h"

namespace radwalk {

// Throws InputError for a bad problem or options.
Solution solve_jacobi(const RadiosityProblem& p, const SolveOptions& options = {});

}  // namespace radwalk
