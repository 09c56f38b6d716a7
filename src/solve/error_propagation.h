#pragma once
// The variance of B = (I - H)^{-1} E, H = diag(rho) F, caused by independent noise in the rows' gathers g = F B.
//
// To first order a perturbation dg of the gathers moves B by dB = (I - H)^{-1} diag(rho) dg, so with independent
// gathers of variance V_j (formfactor/form_factor_noise.h)
//   Var(B_i) = sum_j G_ij^2 q_j,     G = (I - H)^{-1},  q_j = rho_j^2 V_j           (per channel),
// the diagonal of G diag(q) G^T. G is never formed: K Gaussian probes z ~ N(0, diag(q)) are solved, x = G z (by
// Jacobi sweeps of x = z + H x, all probes and channels at once, to a relative change below 1e-6; over MPI each
// process sweeps the rows of F it holds and the rows are shared, the same result bit for bit; when some rho >= 0.99,
// as the re-radiating rows of the net-radiation system, on one process by the block GMRES of block_gmres.h to a
// relative residual below 1e-6 per column, since the sweeps' rate is then close to 1), and
//   Var(B_i) ~ q_i + (1/K) sum_k (x_ik^2 - z_ik^2),
// an unbiased estimate (E z_i^2 = q_i) whose noise comes only from what the other rows add (x - z): the row's own
// gather, usually the largest part, enters exactly. Since G_ii >= 1 the result is never below q_i (clamped there).
// Derivation: docs/theory/error_estimate.md. Cost: 3 K multiply-adds per non-zero of F per sweep. Reproducible: probes from the stream (seed, error_estimate, 1 + k), independent of the thread count.
#include <cstdint>

#include "core/types.h"
#include "solve/problem.h"

namespace radwalk {

struct PropagatedVariance {
  PatchRgb variance;  // Var(B_i) per patch and channel
  int probes = 0;     // K
  long sweeps = 0;
  double seconds = 0;
};

// p's F: every row, or over MPI this process's row block (p.row_blocks; collective then). gather_variance: V
// (N x 3, >= 0, every row). probes K >= 1.
// Throws InputError if the sweeps do not converge within 10,000 (spectral radius of H near or above 1).
PropagatedVariance propagate_gather_variance(const RadiosityProblem& p, const PatchRgb& gather_variance,
                                             int probes = 16, std::uint64_t seed = 1);

}  // namespace radwalk
