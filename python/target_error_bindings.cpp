// radwalk.solve_to_target_error: accuracy on request (solve/target_error.h) as `radwalk solve SCENE --target-error
// E` runs it: each step traces F by the recommended route (Sobol rays, automatic emitter columns) with the step's
// rays, solves with the automatic solver, and estimates B_se and B_disc as radwalk.solve does; the same seed
// gives the CLI's patches and B.
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "apps/run_metadata.h"
#include "bindings.h"
#include "core/parallel.h"
#include "formfactor/emitter_form_factors.h"
#include "hierarchy/hierarchical_target_error.h"
#include "hierarchy/leaf_patches.h"
#include "hierarchy/start_by_edge_length.h"
#include "interruptible.h"
#include "solve/target_error.h"
#include "solve/target_error_stage.h"
#include "visibility/embree_visibility.h"

namespace radwalk::python {
namespace {

struct TargetErrorPyResult {
  Scene scene;                     // the last step's patches
  FormFactorsResult form_factors;  // their F
  Result result;                   // their solve, with B_se and B_disc
  std::vector<TargetErrorStep> steps;
  std::vector<GroupMeanError> groups;  // the last step's, when the run held each group's mean
  bool reached = false;
  std::string stop_reason;
};

// The groups whose means the run holds, as the CLI's --target-each: None -> "material" where the route can hold
// it (not hierarchical_transport="rays"), else none; "none" -> none (""); an unknown name is refused by the route.
std::string held_groups(const std::optional<std::string>& each, bool can_hold) {
  if (!each) return can_hold ? "material" : "";
  return *each == "none" ? "" : *each;
}

// One step's work of the uniform route (the CLI's defaults: Sobol rays, automatic emitter columns, the automatic
// solver), B_se and B_disc as radwalk.solve estimates them; also the hierarchical route's form-factor transport, which
// also asks for the shooter shares (attribute_shooters; apps/target_error.h says why the uniform route does not).
TargetErrorWork form_factor_work(std::uint64_t seed, double tol, int discretisation_directions,
                                 bool attribute_shooters) {
  return [=](const PatchSet& p, long step_rays, int) {
    const EmbreeVisibility visibility(p);
    FormFactorOptions o;  // the CLI's defaults: the recommended route
    o.rays_per_patch = step_rays;
    o.seed = seed;
    o.sobol = true;
    return solve_target_error_stage(p, visibility,
                                    estimate_form_factors_with_emitters(p, visibility, o, kAutoEmitterSamples),
                                    {tol, discretisation_directions, seed, attribute_shooters});
  };
}

// hierarchical=True: `radwalk solve SCENE --hierarchical --target-error E` (hierarchy/hierarchical_target_error.h
// with the CLI's defaults: 8 levels, 16 direct-light points a leaf to start, 4 replicates): rays is the first step's
// rays per leaf, max_patches the budget of leaves; transport "form-factors" (the leaves solved by the uniform
// route's work; form_factors holds the last step's F) or "rays" (no form factors: form_factors holds an empty F).
TargetErrorPyResult hierarchical_to_target_error(const Scene& scene, double target_error, long rays, long max_patches,
                                                 double max_seconds, double tol, std::uint64_t seed, int threads,
                                                 int discretisation_directions, const std::string& transport,
                                                 const std::string& split, const std::optional<std::string>& each) {
  HierarchicalOptions h;
  h.seed = seed;
  HierarchicalTargetOptions o;
  o.target = target_error;
  o.rays_per_leaf = rays;
  o.max_leaves = max_patches;
  o.max_seconds = max_seconds;
  o.directions = discretisation_directions;
  o.each = held_groups(each, transport == "form-factors");
  o.split = split;
  if (scene.max_edge == 0 && scene.max_area == 0) o.start_leaves = kStartMoreElements;
  HierarchicalTargetResult r;
  interruptible([&] {
    ThreadLimit limit(threads);
    const EmbreeVisibility visibility(scene.patches);
    const TargetErrorWork leaf_work =
        transport == "form-factors" ? form_factor_work(seed, tol, discretisation_directions, true) : TargetErrorWork{};
    r = solve_hierarchical_to_target_error(scene.patches, visibility, h, o, {}, leaf_work);
  });
  if (r.form_factor_transport) check_solved(r.stage.solution);
  TargetErrorPyResult out;
  out.scene = refined_scene(scene, leaf_patches(scene.patches, r.solution.tree, r.solution.leaves));
  out.form_factors.area = out.scene.patches.area;
  if (r.form_factor_transport) out.form_factors.ff = std::move(r.stage.form_factors);
  for (const HierarchicalTargetStep& s : r.steps) out.steps.push_back(s.step);
  out.groups = r.groups;
  out.reached = r.reached;
  out.stop_reason = r.stop_reason == "max-leaves" ? "max-patches" : r.stop_reason;
  out.result.solution = hierarchical_target_solution(r);
  out.result.timings = {{"target_error", r.seconds}};
  nlohmann::json target = {{"target", target_error},    {"route", "hierarchical"}, {"transport", transport},
                           {"max_patches", max_patches},
                           {"max_seconds", max_seconds}, {"reached", out.reached}, {"stop_reason", out.stop_reason},
                           {"seconds", r.seconds},      {"steps", nlohmann::json::array()},
                           {"each", o.each.empty() ? "none" : o.each}};
  if (!o.each.empty()) target["groups"] = app::group_mean_errors_json(out.groups);
  for (const HierarchicalTargetStep& s : r.steps) {
    nlohmann::json x = app::target_error_step_json(s.step);
    x["leaves"] = s.step.patches;
    x["rays"] = s.rays;
    target["steps"].push_back(x);
  }
  nlohmann::json run = {{"solver", "hierarchical"}, {"seed", seed}, {"threads", threads},
                        {"rays_per_leaf", out.steps.back().rays_per_patch}, {"target_error", target}};
  out.result.metadata = result_metadata(out.result, out.scene, run);
  return out;
}

TargetErrorPyResult solve_to_target_error_py(const Scene& scene_arg, double target_error, long rays, long max_patches,
                                             double max_seconds, double tol, std::uint64_t seed,
                                             long long threads_arg, int discretisation_directions, bool hierarchical,
                                             const std::string& hierarchical_transport,
                                             const std::optional<std::string>& hierarchical_split_arg,
                                             const std::optional<std::string>& each) {
  const int threads = check_run(scene_arg, threads_arg);
  if (discretisation_directions < 1)
    throw InputError("solve_to_target_error needs the discretisation estimate: discretisation_directions must be "
                     ">= 1, got " + std::to_string(discretisation_directions));
  if (max_patches < 1) throw InputError("max_patches must be >= 1, got " + std::to_string(max_patches));
  if (hierarchical_transport != "form-factors" && hierarchical_transport != "rays")
    throw InputError("hierarchical_transport must be \"form-factors\" or \"rays\", got \"" + hierarchical_transport +
                     "\"");
  if (!hierarchical && hierarchical_transport != "form-factors")
    throw InputError("hierarchical_transport applies only with hierarchical=True (the default): remove it");
  const std::string hierarchical_split = hierarchical_split_arg.value_or("adaptive");
  if (hierarchical_split != "regular" && hierarchical_split != "adaptive")
    throw InputError("hierarchical_split must be \"regular\" or \"adaptive\", got \"" + hierarchical_split + "\"");
  if (!hierarchical && hierarchical_split_arg)
    throw InputError("hierarchical_split applies only with hierarchical=True (the default): remove it");
  if (hierarchical && tol != 1e-10 && hierarchical_transport == "rays")
    throw InputError("tol does not apply with hierarchical=True and hierarchical_transport=\"rays\" (the "
                     "hierarchical solver shoots until the unshot power is below 1e-6 of the first shot's): remove it");
  // Its own split comes after the cut along the contacts (the CLI's --target-error cuts as it loads); the options
  // are checked first, so that a refusal costs no patching.
  const Scene cut = scene_arg.uncut_mesh ? cut_for_splitting(scene_arg) : Scene();
  const Scene& scene = scene_arg.uncut_mesh ? cut : scene_arg;
  if (hierarchical) {
    return hierarchical_to_target_error(scene, target_error, rays, max_patches, max_seconds, tol, seed, threads,
                                        discretisation_directions, hierarchical_transport, hierarchical_split, each);
  }
  TargetErrorOptions options;
  options.target = target_error;
  options.rays = rays;
  options.max_patches = static_cast<std::size_t>(max_patches);
  options.max_seconds = max_seconds;
  options.each = held_groups(each, true);
  if (scene.max_edge == 0 && scene.max_area == 0) options.start_patches = kDefaultStartPatches;
  const TargetErrorWork work = form_factor_work(seed, tol, discretisation_directions, false);
  TargetErrorResult r;
  interruptible([&] {
    ThreadLimit limit(threads);
    r = solve_to_target_error(scene.patches, work, options);
  });
  check_solved(r.solution);
  TargetErrorPyResult out;
  out.scene = refined_scene(scene, std::move(r.patches));
  out.form_factors.area = out.scene.patches.area;
  out.form_factors.ff = std::move(r.form_factors);
  out.steps = std::move(r.steps);
  out.groups = std::move(r.groups);
  out.reached = r.reached;
  out.stop_reason = r.stop_reason;
  out.result.solution = std::move(r.solution);
  out.result.timings = {{"target_error", r.seconds}};
  nlohmann::json target = {{"target", target_error},    {"max_patches", max_patches}, {"max_seconds", max_seconds},
                           {"reached", out.reached},    {"stop_reason", out.stop_reason}, {"seconds", r.seconds},
                           {"steps", nlohmann::json::array()},
                           {"each", options.each.empty() ? "none" : options.each}};
  if (!options.each.empty()) target["groups"] = app::group_mean_errors_json(out.groups);
  for (const TargetErrorStep& s : out.steps) target["steps"].push_back(app::target_error_step_json(s));
  nlohmann::json run = {{"solver", "auto"}, {"tol", tol}, {"seed", seed}, {"threads", threads},
                        {"rays_per_patch", out.steps.back().rays_per_patch}, {"target_error", target}};
  out.result.metadata = result_metadata(out.result, out.scene, run);
  return out;
}

}  // namespace

void bind_target_error(py::module_& m) {
  py::class_<TargetErrorPyResult>(m, "TargetErrorResult", R"doc(What solve_to_target_error() returns.

scene: a Scene of the last step's patches (each keeps its input face, group and material); form_factors: their
FormFactors; result: their Result (B, B_se, B_disc, B_err; metadata holds the CLI's JSON "target_error" object);
steps: one dict per step (patches, rays_per_patch, statistical, discretisation, total: relative errors; seconds;
split, next_rays_per_patch: what the next step changed); reached: whether the estimated total error is at most the
target; stop_reason: "target reached", "max-patches", "depth" (hierarchical: no leaf to split within the depth bounds),
"max-seconds", "max-steps", "rays" or "solver".)doc")
      .def_readonly("scene", &TargetErrorPyResult::scene, "The Scene of the last step's patches, N of them.")
      .def_readonly("form_factors", &TargetErrorPyResult::form_factors, "The FormFactors of those patches, (N, N).")
      .def_readonly("result", &TargetErrorPyResult::result,
                    "The Result of the last solve: B, B_se, B_disc, B_err (N, 3) float64 in W per unit length squared.")
      .def_property_readonly(
          "steps",
          [](const TargetErrorPyResult& a) {
            py::list l;
            for (const TargetErrorStep& s : a.steps) l.append(json_to_python(app::target_error_step_json(s).dump()));
            return l;
          },
          "One dict per step (a list): patches, rays_per_patch, statistical, discretisation, total (relative "
          "errors), seconds, split, next_rays_per_patch (the JSON's target_error.steps).")
      .def_property_readonly(
          "groups",
          [](const TargetErrorPyResult& a) { return json_to_python(app::group_mean_errors_json(a.groups).dump()); },
          "One dict per material (object, group) whose mean the run held, of the last step (a list; empty with "
          "each=\"none\"): name, area, mean, estimate (the signed relative discretisation error of the mean), "
          "discretisation, statistical, total (relative errors of the mean; the JSON's target_error.groups), "
          "statistical_kind (\"first-order\", or \"bound\" where F's noise has no model) and statistical_bound "
          "(the patches' B_se added as if fully correlated).")
      .def_readonly("reached", &TargetErrorPyResult::reached, "Whether the target was reached (bool).")
      .def_readonly("stop_reason", &TargetErrorPyResult::stop_reason, "Why the steps stopped (str).")
      .def("__repr__", [](const TargetErrorPyResult& a) {
        return "<radwalk.TargetErrorResult " + std::to_string(a.scene.patches.size()) + " patches after " +
               std::to_string(a.steps.size()) + " steps (" + a.stop_reason + ")>";
      });

  m.def("solve_to_target_error", &solve_to_target_error_py, py::arg("scene"), py::arg("target_error"),
        py::arg("rays") = 1000, py::arg("max_patches") = 20000, py::arg("max_seconds") = 0.0,
        py::arg("tol") = 1e-10, py::arg("seed") = 1, py::arg("threads") = 0,
        py::arg("discretisation_directions") = 16, py::arg("hierarchical") = true,
        py::arg("hierarchical_transport") = "form-factors", py::arg("hierarchical_split") = py::none(),
        py::arg("each") = py::none(),
        R"doc(Accuracy on request: solve in steps until the estimated total error is at most target_error: a TargetErrorResult.

As `radwalk solve SCENE --target-error TARGET_ERROR --rays RAYS --max-patches MAX_PATCHES --max-seconds
MAX_SECONDS --seed SEED` (docs/accuracy.md "Accuracy on request"): target_error is the area-weighted RMS relative
total error over the reflecting patches (dimensionless, e.g. 0.01); each step solves with its rays per patch (or
leaf; rays: the first step's) and estimates B_se and B_disc; where the statistical part dominates the next step
has more rays, where the discretisation part dominates the elements with the largest estimated error are split.
Its faces are first cut along the contacts when the scene was loaded with contact_cut=True (the default), as the
CLI's --target-error does. each (the CLI's --target-each): also hold each "material" (the default, None), "object"
or "group" mean within 0.8 x target_error (a margin for its estimate's own error), with its own estimated error (the patches of one material have correlated
errors, so its mean can be off by more than the per-patch RMS); "none": the per-patch target alone
(hierarchical_transport="rays" holds none by default and refuses a group). max_patches bounds the patches
(leaves), max_seconds (0: none) the run's time. The same seed gives the CLI's patches and B. When a budget stops it
first, reached is False (the CLI exits 1) and the last, most accurate, solution is returned. The scene passed in is
not changed. The GIL is released during the whole run. Raises radwalk.InputError for options out of range.

hierarchical=True (the default; the CLI's default route, src/hierarchy/hierarchical_target_error.h,
docs/hierarchy.md): the element trees of the patches (of a scene loaded without max_edge or max_area: first split
by edge length to about 200 leaves more than its patches, as the CLI's) are refined by the estimate, leaves split
where the discretisation part dominates (each step the fewest leaves that hold 70 % of the estimated error:
Doerfler's marking) and rays added where the statistical part does; rays is the first step's rays per leaf,
max_patches the budget of leaves; scene holds the leaves (each with its input face). hierarchical_transport:
"form-factors" (default; each step's leaves solved as patches: F traced by the recommended route, the automatic
solver; form_factors the last step's F) or "rays" (hierarchical stochastic Jacobi; form_factors an empty F, tol
does not apply: InputError if given). hierarchical_split (the CLI's --hierarchical-split): "adaptive" (the default:
a quad may be cut in four bands across the direction its light varies in, or across its length where it is long;
docs/hierarchy.md "Band splits") or "regular" (every leaf split in four quarters).

hierarchical=False (the CLI's --target-route uniform, src/solve/target_error.h): the patches themselves are split
in 4 where the discretisation part dominates; a scene loaded without max_edge or max_area starts from about 500
patches (every patch above twice the mean area of 500 split in 4); hierarchical_transport and hierarchical_split
are refused. It does not reach 2 % where light grazes a wall next to a light (docs/accuracy.md, "Where the uniform
route fails").)doc");
}

}  // namespace radwalk::python
