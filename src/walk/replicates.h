#pragma once
// Replicated shooting (WalkSampler::sobol, random_walk_solver.cpp, and WalkSampler::jacobi, stochastic_jacobi.h):
// R = options.replicates independent randomisations r = 0 .. R-1 of one estimate, each B_r unbiased for B, whose
// spread gives the error bars. What the two samplers share:
//   - the particles of replicate r: n_r = particles / R, the first particles % R replicates one more (sum n_r =
//     particles);
//   - its start: the source S_r its particles shoot and the base B_r their scores add to, S_r = E and B_r = E, or,
//     with the direct light apart (direct_light.h), S_r = D_r and B_r = E + D_r (the particles then carry the
//     indirect light only);
//   - the estimate B = mean_r B_r, its standard error se = s_R / sqrt(R) from the spread s_R of the replicates
//     (R - 1 degrees of freedom), and var = se^2 x particles (the per-particle variance an i.i.d. run of the same
//     error would have, so that se = sqrt(var / particles) as for the random sampler).
// How each sampler runs its replicates differs (Sobol: the chunks of all replicates in one pass; Jacobi: bounce by
// bounce within a replicate), so the loop over them is each sampler's own.
#include <cstdint>
#include <functional>
#include <vector>

#include "core/types.h"
#include "walk/transition_kernel.h"
#include "walk/walk_options.h"

namespace radwalk {

// n_r above (options.replicates >= 1).
long replicate_particles(const WalkOptions& options, int r);

// The direct light D_r of replicate r (direct_light.h), adding its shadow rays to the counters; empty: no direct
// light apart (S_r = E).
using ReplicateDirectLight = std::function<PatchRgb(std::uint64_t replicate, WalkCounters& counters)>;

struct ReplicateStart {
  PatchRgb source;  // S_r: E, or D_r
  PatchRgb base;    // B_r before the particles' scores: E, or E + D_r
};
ReplicateStart replicate_start(const PatchRgb& E, int r, const ReplicateDirectLight& direct, WalkCounters& counters);

struct ReplicateEstimate {
  PatchRgb B, se, var;  // N x 3 each
};
// B, se and var above from the replicates' B_r (at least 2), for `particles` particles in all.
ReplicateEstimate replicate_estimate(const std::vector<PatchRgb>& B_r, long particles);

}  // namespace radwalk
