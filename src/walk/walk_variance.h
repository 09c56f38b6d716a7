#pragma once
// Exact variances of the random-walk estimators with the matrix kernel (dense algebra), and the finite-variance
// check. Notation as in transition_kernel.h: per channel, H = diag(rho) F, survival p_k, row scale n_k, row sum
// s_k, gathering transition P_kj = p_k F_kj / n_k, weight w_k = rho_k n_k / p_k.
//
// Gathering: the second moment s_i = E[X_i^2] of a walk from i obeys s = c + K s with
//   K_kl = H_kl^2 / P_kl = (rho_k^2 n_k / p_k) F_kl,   so s = G c, G = (I - K)^-1, finite iff radius(K) < 1;
// with c the estimator's own source term (its static moment_source, next to the estimator class; the
// terms it is made of are moment_terms.h):
//   absorption      c_k = E_k^2 / q_k,  q_k = 1 - p_k s_k / n_k          var_i = s_i - B_i^2
//   collision       c_k = E_k (2 B_k - E_k)                              var_i = s_i - B_i^2
//   expected value  c_k = g_k (2 (B_k - E_k) - g_k),  g = H E          var_i = s_i - (B_i - E_i)^2
//   (for expected value s is the second moment of Y = X - E_i = sum_m W_m g_{k_m}).
// Shooting (shoot_estimators.h), per particle, in radiosity units Y_j = (reflected power scored at j) / A_j,
// with F standing for the walked rows T = A^-1 F^T A (= F when F is reciprocal; matrix_kernel.h) and n for their
// row scales:
//   E[Y_j^2] = c_j / A_j^2 * sum_i (S_i^2 / pi_i) [(I - N F D)^-1 N F]_ij,  S = A.*E, D = diag(rho^2 / p),
//   N = diag(n), pi = birth probabilities; with m_j = rho_j [(I - F diag(rho))^-1 F]_jj (expected later score at
//   j of a unit weight leaving j):
// (c_j again each estimator's moment_source)
//   collision   c_j = rho_j^2 (1 + 2 m_j),   absorption  c_j = rho_j^2 / (1 - p_j),
//   survival    c_j = rho_j^2 (1 + 2 m_j) / p_j;               var_j = E[Y_j^2] - (B_j - E_j)^2.
//   N F D has the spectrum of diag(rho^2 n / p) F, so the radius of that K (over T) decides finiteness.
#include "core/types.h"
#include "solve/problem.h"
#include "walk/walk_options.h"

namespace radwalk {

// Largest N for the dense computations here (O(N^3) time, O(N^2) memory).
inline constexpr std::size_t kMaxTheoryPatches = 2000;

// B from a dense LU of (I - diag(rho_c) F) per channel. InputError above kMaxTheoryPatches.
PatchRgb dense_radiosity(const RadiosityProblem& problem);

// Per-walk (gathering) or per-particle (shooting) variance of the estimator in `options` with the matrix kernel
// and options.survival, for every patch, per channel; +inf where the variance is infinite (radius(K) >= 1).
// B_exact: the solution for the same F (dense_radiosity). InputError above kMaxTheoryPatches patches.
PatchRgb theoretical_variance(const RadiosityProblem& problem, const WalkOptions& options, const PatchRgb& B_exact);

struct VarianceCheck {
  double radius = 0;  // spectral radius estimate of K, max over channels
  double upper = 0;   // Collatz-Wielandt upper bound
  int channel = 0;    // channel attaining it
  bool finite() const { return radius < 1; }
};

// Spectral radius of K_c = diag(rho_c^2 n / p) F over the rows walked (F, or T for matrix shooting; power
// iteration on the sparse K, solve/spectral_radius.h). For the ray kernel the stored F stands in for the exact one.
VarianceCheck check_finite_variance(const RadiosityProblem& problem, const WalkOptions& options);

}  // namespace radwalk
