#include "apps/target_error.h"

#include <utility>

#include "apps/discretisation_error.h"
#include "apps/pipeline.h"
#include "apps/run_metadata.h"
#include "apps/statistical_error.h"
#include "core/error.h"
#include "solve/problem.h"
#include "solve/solve_radiosity.h"

namespace radwalk::app {

TargetErrorWork form_factor_target_work(const SolveCommand& command, RunSummary& summary, std::string& error_line,
                                        bool first_obtains, bool attribute_shooters) {
  return [&command, &summary, &error_line, first_obtains, attribute_shooters](const PatchSet& p, long rays, int step) {
    FormFactorCliOptions ff_options = command.ff;
    ff_options.rays = rays;
    TargetErrorStage stage;
    stage.form_factors = step == 0 && first_obtains ? obtain_form_factors(command.scene, ff_options, p, summary)
                                                    : trace_form_factors(command.scene, ff_options, p);
    // A copy of F for the solve: the last step's F stays with its record, for the per-patch diagnostics.
    const RadiosityProblem problem = make_problem(p, SparseF(stage.form_factors.F));
    SolveOptions solve;
    solve.tol = command.tol;
    solve.max_iterations = default_max_iterations(solve.solver, p.size());
    stage.solution = solve_radiosity(problem, solve);
    if (stage.solution.status == SolveStatus::converged) {
      error_line = add_statistical_error(p, stage.form_factors, problem, stage.solution, summary);
      const std::string disc = add_discretisation_error(p, problem, stage.solution, summary,
                                                        command.discretisation_directions, command.scene.seed,
                                                        attribute_shooters ? &stage.shooter_share : nullptr);
      if (!disc.empty()) error_line += "\n" + disc;
    }
    return stage;
  };
}

TargetErrorRun run_target_error(const SolveCommand& command, PatchSet patches, RunSummary& summary) {
  if (command.discretisation_directions <= 0)
    throw InputError("--target-error needs the discretisation estimate: --discretisation-directions must be > 0");
  TargetErrorOptions options;
  options.target = command.target_error;
  options.rays = command.ff.rays;
  options.max_patches = static_cast<std::size_t>(command.max_patches);
  options.max_seconds = command.max_seconds;
  if (command.scene.max_edge == 0 && command.scene.max_area == 0) options.start_patches = kDefaultStartPatches;
  TargetErrorRun run;
  const TargetErrorWork work = form_factor_target_work(command, summary, run.error_line, true);
  const auto report = [](const TargetErrorStep& s, int step) {
    note("target error step " + std::to_string(step) + ": " + std::to_string(s.patches) + " patches, " +
         std::to_string(s.rays_per_patch) + " rays a patch: estimated error " + percent(s.total) + " (statistical " +
         percent(s.statistical) + ", discretisation " + percent(s.discretisation) + "), " +
         std::to_string(s.seconds) + " s" +
         (s.next_rays_per_patch > 0 ? "; next: " + std::to_string(s.split) + " patches split, " +
                                          std::to_string(s.next_rays_per_patch) + " rays a patch"
                                    : std::string()));
  };
  run.result = solve_to_target_error(std::move(patches), work, options, report);
  const TargetErrorResult& r = run.result;
  auto& j = summary.json()["target_error"];
  j["target"] = options.target;
  j["max_patches"] = options.max_patches;
  j["max_seconds"] = options.max_seconds;
  j["reached"] = r.reached;
  j["stop_reason"] = r.stop_reason;
  j["seconds"] = r.seconds;
  j["steps"] = nlohmann::json::array();
  for (const TargetErrorStep& s : r.steps) j["steps"].push_back(target_error_step_json(s));
  summary.json()["patches"] = r.patches.size();
  summary.json()["rays_per_patch"] = r.steps.back().rays_per_patch;
  summary.add_timing("target_error", r.seconds);
  return run;
}

}  // namespace radwalk::app
