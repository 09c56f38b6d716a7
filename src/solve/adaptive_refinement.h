#pragma once
// Adaptive patching: solve, split the patches whose radiosity differs from a neighbour's, re-solve, repeat.
//
// Step k = 0, 1, ...: F = form_factors(patches); B = solve_radiosity(make_problem(patches, F), solve); then
//   - stop ("solver") if the solve did not converge, ("steps") if k == max_steps;
//   - jump_i = radiosity_jumps(patches, B, edge_neighbours(patches), floor_fraction, H_se, noise_z)
//     (refine_criterion.h), with H_se = irradiance_standard_error(F, B, rays) when F was estimated by rays
//     (differences within noise_z standard errors do not split) and, with visible_from_back_hits, the visible
//     fraction of patch i estimated as 1 - back_hits_i / rays_i (a ray leaving the part of a patch inside a closed
//     object, like the floor under a block, hits the back of that object's faces);
//     marked = { i : jump_i > tol }; stop ("converged") if none is marked;
//   - split the marked patches (refine.h: 4 children each, T-junctions allowed); if that would exceed
//     max_patches, split only the floor((max_patches - N) / 3) marked patches with the largest jumps (ties:
//     lower index) and stop ("max-patches") after the next solve; stop at once if not even one fits.
// The result holds the last patches, their form factors and solution, and one record per solve.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "formfactor/form_factors.h"
#include "patch/patch_set.h"
#include "patch/refine_criterion.h"
#include "core/solution.h"
#include "solve/solve_options.h"

namespace radwalk {

struct RefineOptions {
  double tol = 0.1;                      // split where jump_i > tol (relative difference, > 0)
  int max_steps = 4;                     // refinement steps (so at most max_steps + 1 solves), >= 0
  std::size_t max_patches = 20000;       // never split beyond this many patches (>= 1)
  double floor_fraction = kDefaultRefineFloorFraction;
  double noise_z = kDefaultRefineNoiseZ;  // significance of a difference against form-factor noise (0: off)
  bool visible_from_back_hits = true;     // compare the irradiance of the visible parts (see above)
};

struct RefineStep {
  int step = 0;
  std::size_t patches = 0;       // patches solved in this step
  std::size_t marked = 0;        // patches with jump > tol after the solve
  std::size_t split = 0;         // patches split after it (marked, or fewer at max_patches; 0 in the last step)
  double max_jump = 0;           // largest jump_i
  std::string method;            // solver used ("direct", "gauss-seidel", ...)
  long iterations = 0;
  double form_factor_seconds = 0, solve_seconds = 0, refine_seconds = 0, seconds = 0;
};

struct RefinedSolution {
  PatchSet patches;          // the last (finest) patches
  FormFactors form_factors;  // their F
  Solution solution;         // their B
  std::vector<double> jump;  // jump_i of the last solve
  std::vector<RefineStep> steps;
  std::string stop_reason;   // "converged", "steps", "max-patches" or "solver"
};

// Standard error of H_i = (F B)_i from the form-factor noise of row i alone: the rays of patch i score B_j of the
// patch j they hit (0 when they escape), so se_ic = sqrt((sum_j F_ij B_jc^2 - (sum_j F_ij B_jc)^2) / n_i).
// rays: n_i per patch (FormFactors::rays). Sizes that disagree and n_i = 0 are InternalError (RADWALK_CHECK).
PatchRgb irradiance_standard_error(const SparseF& F, const PatchRgb& B, const std::vector<std::uint32_t>& rays);

using FormFactorStage = std::function<FormFactors(const PatchSet&)>;

// Throws InputError for options out of range (and whatever the stages throw). on_step, if set, is called after
// each step's record is complete (for progress output).
RefinedSolution solve_adaptive(PatchSet patches, const FormFactorStage& form_factors, const SolveOptions& solve,
                               const RefineOptions& refine,
                               const std::function<void(const RefineStep&)>& on_step = {});

}  // namespace radwalk
