#include "apps/target_error.h"

#include <utility>

#include "apps/discretisation_error.h"
#include "apps/pipeline.h"
#include "apps/run_metadata.h"
#include "apps/statistical_error.h"
#include "core/error.h"
#include "solve/problem.h"
#include "solve/solve_radiosity.h"
#include "solve/target_error_stage.h"
#include "visibility/embree_visibility.h"

namespace radwalk::app {

std::string target_groups(const SolveCommand& command, bool can_hold) {
  if (command.target_each.empty()) return can_hold ? "material" : "";
  return command.target_each == "none" ? "" : command.target_each;
}

std::string group_progress(const TargetErrorStep& s, const std::string& each, double target) {
  if (s.groups == 0) return {};
  return "; " + std::to_string(s.groups_within) + " of " + std::to_string(s.groups) + " " + each + "s within " +
         percent(group_target(target)) + " (largest: " + s.worst_group + " " + percent(s.worst_group_total) +
         ")";
}

TargetErrorWork form_factor_target_work(const SolveCommand& command, RunSummary& summary, std::string& error_line,
                                        bool first_obtains, bool attribute_shooters) {
  return [&command, &summary, &error_line, first_obtains, attribute_shooters](const PatchSet& p, long rays, int step) {
    FormFactorCliOptions ff_options = command.ff;
    ff_options.rays = rays;
    FormFactors ff = step == 0 && first_obtains ? obtain_form_factors(command.scene, ff_options, p, summary)
                                                : trace_form_factors(command.scene, ff_options, p);
    // The step shared with radwalk.solve_to_target_error (solve/target_error_stage.h); its estimates reported here.
    TargetErrorStageEstimates estimates;
    TargetErrorStage stage = solve_target_error_stage(
        p, EmbreeVisibility(p), std::move(ff),
        {command.tol, command.discretisation_directions, command.scene.seed, attribute_shooters}, &estimates);
    // When the run holds each material's mean it computes the materials' means itself (step_group_errors, the
    // same numbers): reported after the run (report_held_materials), not computed twice a step.
    const bool report_materials = target_groups(command, true) != "material";
    if (stage.solution.status == SolveStatus::converged) {
      const FormFactorError* statistical = estimates.statistical ? &*estimates.statistical : nullptr;
      error_line = report_statistical_error(p, stage.form_factors, stage.solution, estimates.solver_standard_error, statistical,
                                            estimates.statistical_seconds, summary);
      if (estimates.discretisation)
        error_line += "\n" + report_discretisation_error(p, *stage.problem, *estimates.discretisation,
                                                         stage.solution, summary, stage.noise, report_materials);
    }
    return stage;
  };
}

void report_held_materials(const std::string& each, TargetErrorRun& run, RunSummary& summary) {
  if (each != "material" || run.result.groups.empty()) return;
  const std::string line = report_material_means(run.result.groups, summary);
  if (!line.empty()) run.error_line += (run.error_line.empty() ? "" : "\n") + line;
}

TargetErrorRun run_target_error(const SolveCommand& command, PatchSet patches, RunSummary& summary) {
  if (command.discretisation_directions <= 0)
    throw InputError("--target-error needs the discretisation estimate: --discretisation-directions must be > 0");
  TargetErrorOptions options;
  options.target = command.target_error;
  options.rays = command.ff.rays;
  options.max_patches = static_cast<std::size_t>(command.max_patches);
  options.max_seconds = command.max_seconds;
  options.each = target_groups(command, true);
  if (command.scene.max_edge == 0 && command.scene.max_area == 0) options.start_patches = kDefaultStartPatches;
  TargetErrorRun run;
  const TargetErrorWork work = form_factor_target_work(command, summary, run.error_line, true);
  const auto report = [&options](const TargetErrorStep& s, int step) {
    note("target error step " + std::to_string(step) + ": " + std::to_string(s.patches) + " patches, " +
         std::to_string(s.rays_per_patch) + " rays a patch: estimated error " + percent(s.total) + " (statistical " +
         percent(s.statistical) + ", discretisation " + percent(s.discretisation) + "), " +
         std::to_string(s.seconds) + " s" +
         group_progress(s, options.each, options.target) +
         (s.next_rays_per_patch > 0 ? "; next: " + std::to_string(s.split) + " patches split, " +
                                          std::to_string(s.next_rays_per_patch) + " rays a patch"
                                    : std::string()));
  };
  run.result = solve_to_target_error(std::move(patches), work, options, report);
  const TargetErrorResult& r = run.result;
  auto& j = summary.json()["target_error"];
  j["route"] = "uniform";
  j["target"] = options.target;
  j["max_patches"] = options.max_patches;
  j["max_seconds"] = options.max_seconds;
  j["reached"] = r.reached;
  j["stop_reason"] = r.stop_reason;
  j["seconds"] = r.seconds;
  j["steps"] = nlohmann::json::array();
  for (const TargetErrorStep& s : r.steps) j["steps"].push_back(target_error_step_json(s));
  j["each"] = options.each.empty() ? "none" : options.each;
  if (!options.each.empty()) j["groups"] = group_mean_errors_json(r.groups);
  report_held_materials(options.each, run, summary);
  summary.json()["patches"] = r.patches.size();
  summary.json()["rays_per_patch"] = r.steps.back().rays_per_patch;
  summary.add_timing("target_error", r.seconds);
  return run;
}

}  // namespace radwalk::app
