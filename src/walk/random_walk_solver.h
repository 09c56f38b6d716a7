#pragma once
// solve_random_walk: the discrete random-walk solvers of B = E + diag(rho) F B behind one call.
//
// Gathering methods estimate B_i for the chosen patches (options.patches, empty = all) from
// options.walks_per_patch independent walks per patch; shooting methods estimate every patch from
// options.particles particles (gather_estimators.h, shoot_estimators.h; the method is dispatched to its estimator
// once, walk_estimators.h). Per patch and channel the Solution holds
//   B     the estimate (gathering: the mean walk score; shooting: E_j + mean reflected-power score / A_j),
//   var   the per-walk (per-particle) sample variance, B_se = sqrt(var / walks),
//   var_theory  with options.theory and the matrix kernel: walk_variance.h (empty otherwise).
// With options.sampler == sobol (shooting): options.replicates independent stratified replicates
// (stratified_emission.h; with options.direct_light the first bounce apart, direct_light.h), B their mean, B_se
// from their spread (R - 1 degrees of freedom), var = B_se^2 x particles; steps include the shadow rays; info holds
// "replicates" (and "shadow_rays_per_patch" on the ray kernel).
// Patches a gathering run did not estimate are NaN. walks, steps (destination samples: alias draws or rays),
// seconds (walks only, without the optional theory) are filled; info holds "variance_radius" (spectral radius of
// K, finite variance iff < 1; NaN when F is not stored), "escapes", "back_hits", "walks_per_patch" or
// "particles", "emitted_power", and for shooting "reflecting_patches" (non-emitting, rho > 0) and
// "unreached_patches" (those of them no particle scored, so B = 0 there). A radius >= 1 keeps the (unbiased)
// estimate but says in `message` that its variance is infinite and its error bars are meaningless; so does a
// shooting run that left more than half of the reflecting patches unreached (too_few_particles).
// Threads: whatever TBB allows (core/parallel.h ThreadLimit); the output does not depend on it.
// Progress: with options.progress a line "random walks (METHOD)" on stderr (core/progress.h); or the caller's
// Progress, advanced by walk_work_items(options, N) in all (compare shows one line over several solves).
#include <string>

#include "patch/patch_set.h"
#include "solve/problem.h"
#include "solve/spectral_radius.h"
#include "core/solution.h"
#include "visibility/visibility.h"
#include "walk/walk_options.h"

namespace radwalk {

class Progress;

// The matrix kernel needs problem.F (N x N); the ray kernel needs `patches` (the same N patches) and
// `visibility`, and ignores F except for the variance radius. Throws InputError on invalid options
// (check_walk_options) or input, including a survival probability p_k >= 1 (a walk might never end) or p_k = 0
// where rho_k > 0 (biased).
Solution solve_random_walk(const RadiosityProblem& problem, const PatchSet* patches, const Visibility* visibility,
                           const WalkOptions& options);
Solution solve_random_walk(const RadiosityProblem& problem, const PatchSet* patches, const Visibility* visibility,
                           const WalkOptions& options, Progress& progress);

// The walks estimate the Neumann series B = sum_m (diag(rho) F)^m E, which diverges when the spectral radius of
// some diag(rho_c) F is 1 or more (within kRadiusOneTolerance, solve/convergence.h: rho = 1 in a closed scene,
// rows of F above 1): the walks would end (p_k < 1) but their weights grow without bound, and no finite B
// exists to estimate. For problem.F stored (N x N): the radius estimated (solve/spectral_radius.h) and, when it
// is that large, `refusal`, one line naming `method`, the radius, its channel, the largest rho and row sum of F
// (empty when the walks may go on). solve_random_walk returns it as a diverged Solution, measure_random_walk
// throws it as a NumericalError.
struct WalkConvergence {
  SpectralRadius radius;
  std::string refusal;
};
WalkConvergence check_walks_converge(const RadiosityProblem& problem, const std::string& method);

// The shadow rays per receiving patch (over all replicates) a Sobol run with direct_light traces on the ray
// kernel: options.shadow_rays, or particles / (2 N) and at least 16 per replicate; 0 without direct_light.
long direct_shadow_rays(const WalkOptions& options, std::size_t patch_count);

// The work items (chunks of walks) a solve with these options advances its Progress by, for N patches.
std::size_t walk_work_items(const WalkOptions& options, std::size_t patch_count);

// A shooting solution whose particles left more than half of the non-emitting reflecting patches at B = 0.
bool too_few_particles(const Solution& solution);

}  // namespace radwalk
