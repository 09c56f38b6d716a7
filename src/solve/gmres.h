#pragma once
// Restarted GMRES(m) for (I - H_c) B_c = E_c, H_c = diag(rho_c) F, one channel at a time, right-preconditioned
// by one forward Gauss-Seidel sweep (docs/theory/net_radiation.md, "The Krylov solver"):
//   A = I - H = D - L - U  (D the diagonal 1 - rho_i F_ii, L and U the strict triangles of H),  M = D - L,
//   solve A M^-1 y = E,  B = M^-1 y.
// A M^-1 = (M - U) M^-1 = I - U M^-1, so one product w = A M^-1 v is the forward substitution z = M^-1 v
// (z_i = (v_i + rho_i sum_{j<i} F_ij z_j) / D_i) followed by w = v - U z: one pass over F, as one Gauss-Seidel
// sweep costs (Eisenstat's trick). Arnoldi by modified Gram-Schmidt, the least-squares problem by Givens
// rotations. Right preconditioning keeps the residual GMRES minimises equal to the residual E - A B of the
// system itself, so its stopping test is the other solvers' (residual.h): after each restart cycle the exact
// residual r = E - A B is computed and the solve stops when max_c ||r_c||_inf / s_c <= tol. Inside a cycle the
// Arnoldi estimate ||r||_2 / s_c (>= the infinity norm) ends the cycle early when it is <= tol.
//
// Unlike the stationary iterations it needs no spectral radius below 1: it converges for every nonsingular
// I - H (in at most N iterations without restarts), and fast when the few eigenvalues of A M^-1 near 0 (the
// nearly conserved modes of re-radiating rows, rho = 1, in a closed scene) are isolated: each costs about one
// Krylov iteration instead of the 1 / (1 - radius) sweeps of Gauss-Seidel. A singular system (every row rho = 1
// and rows of F summing to 1) stalls: it ends as max_iterations with the residual reached.
// Channels with the same rho and E as an earlier channel are copied, not solved again. iterations = products
// with A M^-1 over all channels solved; residual_history holds the Arnoldi estimate ||r||_2 / s_c per iteration.
// options.on_iterate is not called (the cycles do not produce iterates of every channel at once). Needs the
// whole F (the dispatcher gathers it over MPI). Sequential.
#include "core/solution.h"
#include "solve/problem.h"
#include "solve/solve_options.h"

namespace radwalk {

// The Krylov space dimension before a restart.
inline constexpr int kGmresRestart = 60;

// Throws InputError for a bad problem or options.
Solution solve_gmres(const RadiosityProblem& p, const SolveOptions& options = {});

}  // namespace radwalk
