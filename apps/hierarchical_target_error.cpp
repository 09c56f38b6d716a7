#include "apps/hierarchical_target_error.h"

#include <cmath>
#include <utility>

#include "apps/pipeline.h"
#include "apps/run_metadata.h"
#include "apps/statistical_error.h"
#include "core/error.h"
#include "hierarchy/hierarchical_target_error.h"
#include "hierarchy/leaf_patches.h"
#include "hierarchy/start_by_edge_length.h"
#include "solve/discretisation_error.h"
#include "visibility/embree_visibility.h"

namespace radwalk::app {

TargetErrorRun run_hierarchical_target_error(const SolveCommand& command, const PatchSet& roots, RunSummary& summary) {
  if (command.discretisation_directions <= 0)
    throw InputError("--target-error needs the discretisation estimate: --discretisation-directions must be > 0");
  HierarchicalOptions h;
  h.max_level = command.hierarchical_levels;
  h.min_area = command.hierarchical_min_area;
  h.points_side = static_cast<int>(std::lround(std::sqrt(static_cast<double>(command.hierarchical_points))));
  h.replicates = command.hierarchical_replicates;
  h.seed = command.scene.seed;
  HierarchicalTargetOptions o;
  o.target = command.target_error;
  o.rays_per_leaf = command.ff.rays;
  o.max_leaves = command.max_patches;
  o.max_seconds = command.max_seconds;
  o.directions = command.discretisation_directions;
  o.split = command.hierarchical_split;
  if (command.scene.max_edge == 0 && command.scene.max_area == 0) o.start_leaves = kStartMoreElements;
  const bool form_factors = command.hierarchical_transport == "form-factors";
  o.each = target_groups(command, form_factors);
  const EmbreeVisibility visibility(roots);
  const auto report = [&o](const HierarchicalTargetStep& r, int step) {
    const TargetErrorStep& s = r.step;
    note("target error step " + std::to_string(step) + " (hierarchical): " + std::to_string(s.patches) + " leaves, " +
         std::to_string(s.rays_per_patch) + " rays a leaf: estimated error " + percent(s.total) + " (statistical " +
         percent(s.statistical) + ", discretisation " + percent(s.discretisation) + "), " + std::to_string(s.seconds) +
         " s" + group_progress(s, o.each, o.target) +
         (s.next_rays_per_patch > 0 ? "; next: " + std::to_string(s.split) + " leaves split, " +
                                          std::to_string(s.next_rays_per_patch) + " rays a leaf" +
                                          (r.band_splits > 0 ? " (" + std::to_string(r.band_splits) + " in bands)"
                                                             : std::string())
                                    : std::string()));
  };
  TargetErrorRun run;
  const TargetErrorWork leaf_work =
      form_factors ? form_factor_target_work(command, summary, run.error_line, false, true) : TargetErrorWork{};
  HierarchicalTargetResult r = solve_hierarchical_to_target_error(roots, visibility, h, o, report, leaf_work);

  TargetErrorResult& t = run.result;
  t.patches = leaf_patches(roots, r.solution.tree, r.solution.leaves);
  t.solution = hierarchical_target_solution(r);
  if (form_factors) t.form_factors = std::move(r.stage.form_factors);
  else t.solution.info["replicates"] = h.replicates;
  for (const HierarchicalTargetStep& s : r.steps) t.steps.push_back(s.step);
  t.groups = r.groups;
  t.reached = r.reached;
  t.stop_reason = r.stop_reason == "max-leaves" ? "max-patches" : r.stop_reason;
  t.seconds = r.seconds;

  const TargetErrorStep& last = t.steps.back();
  auto& e = summary.json()["error_estimate"];
  if (form_factors) {  // B_se and B_disc are the uniform route's (the leaf solver wrote them and the line)
    e["total"] = {{"relative", last.total}, {"combination", "B_err = sqrt(B_se^2 + B_disc^2)"}};
    report_held_materials(o.each, run, summary);  // the leaf work left them to the run (apps/target_error.h)
  } else {
  e["statistical"] = {{"relative", last.statistical},
                      {"method", "the spread of " + std::to_string(h.replicates) +
                                     " independent replicates of the shooting, with the direct light's variance"}};
  e["discretisation"] = {
      {"relative", last.discretisation},
      {"directions_per_point", command.discretisation_directions},
      {"form_factors", "the estimate's own rays"},
      {"method", "the within-patch fluctuation of a one-bounce gather on the leaves as patches, shot with common "
                 "random numbers: e = (I - H)^-1 d, B_disc the root mean square of e given its estimate, with a prior "
                 "fitted over the leaves (docs/theory/discretisation_error.md)"}};
  e["total"] = {{"relative", last.total}, {"combination", "B_err = sqrt(B_se^2 + B_disc^2)"}};
  run.error_line = "estimated error e = " + percent(last.total) + " (statistical " + percent(last.statistical) +
                   ", discretisation " + percent(last.discretisation) +
                   "; 1 standard deviation, relative to B over the reflecting leaves)";
  }

  auto& j = summary.json()["target_error"];
  j["target"] = o.target;
  j["route"] = "hierarchical";
  j["transport"] = command.hierarchical_transport;
  j["max_patches"] = o.max_leaves;
  j["max_seconds"] = o.max_seconds;
  j["reached"] = t.reached;
  j["stop_reason"] = t.stop_reason;
  j["seconds"] = t.seconds;
  j["each"] = o.each.empty() ? "none" : o.each;
  if (!o.each.empty()) j["groups"] = group_mean_errors_json(r.groups);
  j["steps"] = nlohmann::json::array();
  for (const HierarchicalTargetStep& s : r.steps) {
    nlohmann::json x = target_error_step_json(s.step);
    x["leaves"] = s.step.patches;
    x["rays"] = s.rays;
    x["estimate_seconds"] = s.estimate_seconds;
    x["band_splits"] = s.band_splits;
    j["steps"].push_back(x);
  }
  const HierarchicalResult& hr = r.solution;
  auto& hj = summary.json()["hierarchy"];
  hj["roots"] = roots.size();
  hj["elements"] = hr.tree.size();
  hj["leaves"] = hr.leaves.size();
  hj["links"] = 0;     // per-ray level choice: no links are stored
  hj["clusters"] = 0;  // clustering of small faces: not in this route
  hj["memory_bytes"] = hr.memory_bytes;
  hj["levels"] = hr.tree.depth() + 1;
  hj["refine"] = "target-error";
  hj["max_level"] = h.max_level;
  hj["min_area"] = h.min_area;
  hj["points"] = h.points_side * h.points_side;
  hj["transport"] = command.hierarchical_transport;
  hj["split"] = o.split;
  long bands = 0;
  for (std::size_t e = 0; e < hr.tree.size(); ++e) bands += hr.tree.split_kind[e] != SplitKind::regular;
  hj["band_splits"] = bands;
  hj["rays"] = hr.rays;
  if (!form_factors) {
    hj["shadow_rays"] = hr.shadow_rays;
    hj["replicates"] = h.replicates;
    hj["iterations"] = hr.iterations;
  }
  summary.json()["patches"] = t.patches.size();
  summary.json()["rays_per_patch"] = last.rays_per_patch;
  summary.add_timing("target_error", t.seconds);
  note("hierarchical: " + std::to_string(roots.size()) + " patches -> " + std::to_string(hr.tree.size()) +
       " elements, " + std::to_string(hr.leaves.size()) + " leaves, " + std::to_string(hr.tree.depth() + 1) +
       " levels");
  return run;
}

}  // namespace radwalk::app
