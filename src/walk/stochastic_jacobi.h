#pragma once
// Stochastic Jacobi (incremental shooting; WalkSampler::jacobi with shoot-collision): the light is propagated bounce
// by bounce, each bounce's power re-shot from the patches in proportion to it (Neumann, Bekaert et al.; the method
// RenderPark recommends), with rays per iteration in proportion to the unshot power.
//
// Replicate r (r = 0 .. R-1, R = options.replicates), n_r = its particles (replicates.h, as the Sobol sampler's):
//   S_0 = E, or D_r (the direct light, direct_light.h) with options.direct_light, and B_r = E (+ D_r);
//   iteration k = 0, 1, ...: Phi_k = sum_j A_j sum_c |S_kc|; n_{r,k} = max(16, round(c Phi_k)) rays with
//   c = n_r (1 - rho_bar) / Phi_0 (rho_bar the area-weighted mean reflectance, so that sum_k n_{r,k} ~ n_r);
//   the rays are allocated and stratified by StratifiedEmission(S_k, A, n_{r,k}) (stratified_emission.h; its
//   shifts from stream (seed, jacobi_shift, j, r << 32 | k), births from (seed, jacobi_shift, 2^47, r << 32 | k))
//   and each ray is one destination sample h of its birth patch j (kernel.sample with the four Sobol uniforms on
//   the ray kernel; the matrix kernel draws from stream (seed, jacobi_shift, 2^46 + w, r << 32 | k)), scoring
//     S_{k+1, h} += rho_h n_j W0_j / (n_{r,k} A_h)      (W0_j = A_j S_kj / pi_j, the emission's weight);
//   then B_r += S_{k+1}. Given S_k, S_{k+1} is unbiased for diag(rho) A^-1 F^T A S_k = diag(rho) T S_k (the
//   shooting operator of shoot_estimators.h), so by induction E[S_k] is the k-th bounce and B_r is unbiased for
//   B up to the truncation: the iterations stop once Phi_k <= 1e-6 Phi_0 (or after 200), leaving a bias of at
//   most that unshot fraction (relative 1e-6 of the power; far below any error this method reaches).
// B = mean_r B_r, B_se from the spread of the replicates (R - 1 degrees of freedom), as the Sobol sampler
// (replicates.h).
// Work per iteration in fixed chunks merged in chunk order: bit-identical for any thread count.
#include "core/types.h"
#include "solve/problem.h"
#include "walk/replicates.h"
#include "walk/transition_kernel.h"
#include "walk/walk_options.h"

namespace radwalk {

struct JacobiResult {
  ReplicateEstimate estimate;  // B, B_se and var
  WalkCounters counters;
  long iterations = 0;  // summed over the replicates
};

// direct: the direct light of replicate r (adds its rays to the counters), or empty for S_0 = E.
template <TransitionKernel K>
JacobiResult run_stochastic_jacobi(const K& kernel, const RadiosityProblem& problem, const WalkOptions& options,
                                   const ReplicateDirectLight& direct);

}  // namespace radwalk
