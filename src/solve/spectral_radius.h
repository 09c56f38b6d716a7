#pragma once
// Spectral radius of H_c = diag(rho_c) F, which decides whether the Neumann series B = sum_k H^k E (Jacobi,
// Gauss-Seidel, Southwell) converges: it does iff radius < 1, at the asymptotic rate radius per Jacobi sweep.
//
// H >= 0 entrywise, so for any x > 0 the Collatz-Wielandt bounds hold:
//   min_{i: x_i > 0} (H x)_i / x_i  <=  radius(H)  <=  max_i (H x)_i / x_i.
// x = 1 gives the cheap upper bound max_i rho_i * sum_j F_ij. The power iteration runs on I + H (same Perron
// vector, keeps x > 0 even where rho_i = 0) and tightens both bounds; the lower bound uses v = H x_{k-1} >= 0,
// whose product H v = s_k H x_k - H x_{k-1} comes free from consecutive iterates. Max over the three channels.
// With a row-distributed F (problem.h) every product is distributed: each rank multiplies its own rows by the
// whole vector, then the ranks exchange the rows of the result (collective), so every number is one process's.
#include "solve/problem.h"

namespace radwalk {

struct SpectralRadius {
  double bound = 0;        // max_c max_i rho_ic * sum_j F_ij (>= radius)
  double lower = 0;        // Collatz-Wielandt lower bound (0 when not iterated)
  double upper = 0;        // Collatz-Wielandt upper bound (= bound when not iterated)
  double estimate = 0;     // best single value: sum(Hx)/sum(x) clamped to [lower, upper]; the bound if not iterated
  int channel = 0;         // channel attaining the estimate
  int products = 0;        // matrix-vector products of the power iteration, all channels (0: bound only)
  double max_row_sum = 0;  // max_i sum_j F_ij (1 in a closed scene)
  double max_rho = 0;      // max_{i,c} rho_ic
};

// The bound only: one pass over F.
SpectralRadius spectral_radius_bound(const RadiosityProblem& p);

// The bound, then the power iteration per distinct rho column until upper - lower <= rel_tol * upper or
// max_products products per channel. Reports progress ("spectral radius (power iteration)", core/progress.h).
SpectralRadius estimate_spectral_radius(const RadiosityProblem& p, int max_products = 300, double rel_tol = 1e-4);

}  // namespace radwalk
