#pragma once
// solve_random_walk: the discrete random-walk solvers of B = E + diag(rho) F B behind one call.
//
// Gathering methods estimate B_i for the chosen patches (options.patches, empty = all) from options.walks
// independent walks per patch; shooting methods estimate every patch from options.walks particles
// (gather_estimators.h, shoot_estimators.h). Per patch and channel the Solution holds
//   B     the estimate (gathering: the mean walk score; shooting: E_j + mean reflected-power score / A_j),
//   var   the per-walk (per-particle) sample variance, B_se = sqrt(var / walks),
//   var_theory  with options.theory and the matrix kernel: walk_variance.h (empty otherwise).
// Patches a gathering run did not estimate are NaN. walks, steps (destination samples: alias draws or rays),
// seconds (walks only, without the optional theory) are filled; info holds "variance_radius" (spectral radius of
// K, finite variance iff < 1; NaN when F is not stored), "escapes", "back_hits", "walks_per_patch" or
// "particles", "emitted_power". A radius >= 1 keeps the (unbiased) estimate but says in `message` that its
// variance is infinite and its error bars are meaningless.
// Threads: whatever TBB allows (core/parallel.h ThreadLimit); the output does not depend on it.
#include "patch/patch_set.h"
#include "solve/problem.h"
#include "core/solution.h"
#include "visibility/visibility.h"
#include "walk/walk_options.h"

namespace radwalk {

// kernel "matrix" needs problem.F (N x N); kernel "ray" needs `patches` (the same N patches) and `visibility`,
// and ignores F except for the variance radius. Throws InputError on invalid options or input, including a
// survival probability p_k >= 1 (a walk might never end) or p_k = 0 where rho_k > 0 (biased).
Solution solve_random_walk(const RadiosityProblem& problem, const PatchSet* patches, const Visibility* visibility,
                           const WalkOptions& options);

}  // namespace radwalk
