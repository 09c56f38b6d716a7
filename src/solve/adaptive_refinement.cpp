#include "solve/adaptive_refinement.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/check.h"
#include "core/error.h"
#include "core/timer.h"
#include "patch/patch_neighbours.h"
#include "patch/refine.h"
#include "solve/problem.h"
#include "solve/solve_radiosity.h"

namespace radwalk {

PatchRgb irradiance_standard_error(const SparseF& F, const PatchRgb& B, const std::vector<std::uint32_t>& rays) {
  const Eigen::Index n = F.rows();
  RADWALK_CHECK_EQ(F.cols(), n);
  RADWALK_CHECK_EQ(B.rows(), n);
  RADWALK_CHECK_EQ(Eigen::Index(rays.size()), n);
  PatchRgb se(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    RADWALK_CHECK_GT(rays[std::size_t(i)], 0u);  // every patch traces at least min_rays >= 1 rays
    Rgb m1 = Rgb::Zero(), m2 = Rgb::Zero();
    for (SparseF::InnerIterator it(F, i); it; ++it) {
      const Rgb b = B.row(it.col()).transpose();
      m1 += double(it.value()) * b;
      m2 += double(it.value()) * b * b;
    }
    se.row(i) = ((m2 - m1 * m1).max(0.0) / double(rays[std::size_t(i)])).sqrt().transpose();
  }
  return se;
}

RefinedSolution solve_adaptive(PatchSet patches, const FormFactorStage& form_factors, const SolveOptions& solve,
                               const RefineOptions& refine, const std::function<void(const RefineStep&)>& on_step) {
  if (!std::isfinite(refine.tol) || !(refine.tol > 0))
    throw InputError("refine tolerance " + number_text(refine.tol) + " must be finite and > 0");
  if (refine.max_steps < 0) throw InputError("refine steps " + std::to_string(refine.max_steps) + " must be >= 0");
  if (refine.max_patches < 1) throw InputError("refine max patches must be >= 1");
  RADWALK_CHECK(form_factors);  // the caller's form-factor stage

  RefinedSolution result;
  bool last = false;  // the budget of patches was used up by the previous split
  for (int step = 0;; ++step) {
    Timer total, timer;
    RefineStep record;
    record.step = step;
    record.patches = patches.size();
    FormFactors ff = form_factors(patches);
    record.form_factor_seconds = timer.seconds();
    // F moves into the problem for the solve (no copy) and back into ff afterwards.
    RadiosityProblem problem = make_problem(patches, std::move(ff.F));
    Solution solution = solve_radiosity(problem, solve);
    ff.F = std::move(problem.F);
    record.solve_seconds = solution.seconds;
    record.method = solution.method;
    record.iterations = solution.iterations;

    timer.reset();
    std::vector<double> jump;
    if (solution.status == SolveStatus::converged) {
      JumpOptions o;
      o.floor_fraction = refine.floor_fraction;
      o.noise_z = refine.noise_z;
      // The noise allowance needs the standard errors only when it is on (noise_z > 0).
      if (refine.noise_z > 0 && !ff.rays.empty()) o.H_se = irradiance_standard_error(ff.F, solution.B, ff.rays);
      if (refine.visible_from_back_hits && !ff.back_hits.empty()) {
        o.visible.resize(patches.size());
        for (std::size_t i = 0; i < patches.size(); ++i)
          o.visible[i] = 1.0 - double(ff.back_hits[i]) / double(std::max<std::uint32_t>(ff.rays[i], 1));
      }
      jump = radiosity_jumps(patches, solution.B, edge_neighbours(patches), o);
    }
    std::vector<bool> marked = mark_jumps(jump, refine.tol);
    record.marked = std::size_t(std::count(marked.begin(), marked.end(), true));
    record.max_jump = jump.empty() ? 0.0 : *std::max_element(jump.begin(), jump.end());

    std::string stop;
    if (solution.status != SolveStatus::converged) stop = "solver";
    else if (last) stop = "max-patches";
    else if (step >= refine.max_steps) stop = "steps";
    else if (record.marked == 0) stop = "converged";
    else {
      const std::size_t room = patches.size() < refine.max_patches ? (refine.max_patches - patches.size()) / 3 : 0;
      if (room == 0) {
        stop = "max-patches";
      } else {
        if (record.marked > room) {
          // Keep the `room` largest jumps.
          std::vector<std::size_t> order(patches.size());
          std::iota(order.begin(), order.end(), std::size_t(0));
          std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return jump[a] > jump[b]; });
          std::fill(marked.begin(), marked.end(), false);
          for (std::size_t k = 0; k < room; ++k) marked[order[k]] = true;
          last = true;
        }
        record.split = std::min(record.marked, room);
        patches = split_patches(patches, marked);
      }
    }
    record.refine_seconds = timer.seconds();
    record.seconds = total.seconds();
    result.steps.push_back(record);
    if (on_step) on_step(record);
    if (!stop.empty()) {
      // `patches` is still the set that was solved: nothing was split in a stopping step.
      result.patches = std::move(patches);
      result.form_factors = std::move(ff);
      result.solution = std::move(solution);
      result.jump = std::move(jump);
      result.stop_reason = stop;
      return result;
    }
  }
}

}  // namespace radwalk
