// radwalk.solve_adaptive: adaptive patching (solve/adaptive_refinement.h) as `radwalk solve --refine TOL` runs it:
// the same form-factor stage for every step (rays, rays_per_area, min_rays, seed; reciprocity if asked), the same
// solver options, the same result for the same seed.
#include <map>
#include <nlohmann/json.hpp>
#include <unordered_map>

#include "apps/run_metadata.h"
#include "bindings.h"
#include "core/parallel.h"
#include "interruptible.h"
#include "formfactor/emitter_form_factors.h"
#include "formfactor/reciprocity.h"
#include "io/run_summary.h"
#include "solve/adaptive_refinement.h"
#include "solve/solve_radiosity.h"
#include "visibility/embree_visibility.h"

namespace radwalk::python {
namespace {

struct AdaptiveResult {
  Scene scene;                     // the final patches (input faces, groups and materials of the original)
  FormFactorsResult form_factors;  // their F
  Result result;                   // their solve (metadata: the CLI's "solution" and "refine" objects)
  std::vector<double> jump;        // jump_i of the last solve
  std::vector<RefineStep> steps;
  std::string stop_reason;
};

AdaptiveResult solve_adaptive_py(const Scene& scene, double refine_tol, int steps, long max_patches,
                                 double floor_fraction, double noise_z, const std::string& solver, double tol,
                                 long max_iterations, long rays, double rays_per_area, long min_rays,
                                 bool reciprocity, std::uint64_t seed, long long threads_arg) {
  const int threads = check_run(scene, threads_arg);
  RefineOptions r;
  r.tol = refine_tol;
  r.max_steps = steps;
  r.max_patches = max_patches > 0 ? static_cast<std::size_t>(max_patches) : 0;
  r.floor_fraction = floor_fraction;
  r.noise_z = noise_z;
  SolveOptions o;  // as the CLI's solve_options(command, max_patches)
  o.solver = solver;
  o.tol = tol;
  o.max_iterations = max_iterations > 0 ? max_iterations
                                        : default_max_iterations(solver, static_cast<std::size_t>(max_patches));
  FormFactorOptions f;
  f.rays_per_patch = rays;
  f.rays_per_area = rays_per_area;
  f.min_rays = min_rays;
  f.seed = seed;
  f.sobol = true;  // the CLI's defaults: the recommended route
  const FormFactorStage stage = [&](const PatchSet& p) {
    const EmbreeVisibility visibility(p);
    FormFactors ff = estimate_form_factors_with_emitters(p, visibility, f, kAutoEmitterSamples);
    if (reciprocity) enforce_reciprocity(ff.F, p.area);
    return ff;
  };
  RefinedSolution refined;
  interruptible([&] {
    ThreadLimit limit(threads);
    refined = solve_adaptive(scene.patches, stage, o, r);
  });
  check_solved(refined.solution);
  AdaptiveResult a;
  a.scene = refined_scene(scene, std::move(refined.patches));
  a.form_factors.area = a.scene.patches.area;
  a.form_factors.ff = std::move(refined.form_factors);
  a.jump = std::move(refined.jump);
  a.steps = std::move(refined.steps);
  a.stop_reason = refined.stop_reason;
  // Timings as the CLI's: every step's form factors, refinement and solve summed.
  double ff_seconds = 0, solve_seconds = 0, refine_seconds = 0;
  nlohmann::json refine = {{"tol", r.tol},
                           {"max_steps", r.max_steps},
                           {"max_patches", r.max_patches},
                           {"floor_fraction", r.floor_fraction},
                           {"noise_z", r.noise_z},
                           {"initial_patches", scene.patches.size()},
                           {"stop_reason", a.stop_reason},
                           {"steps", nlohmann::json::array()}};
  for (const RefineStep& s : a.steps) {
    refine["steps"].push_back(app::refine_step_json(s));
    ff_seconds += s.form_factor_seconds;
    solve_seconds += s.solve_seconds;
    refine_seconds += s.refine_seconds;
  }
  a.result.solution = std::move(refined.solution);
  a.result.solution.seconds = solve_seconds;
  a.result.timings = {{"form_factors", ff_seconds}, {"refine", refine_seconds}, {"solve", solve_seconds}};
  a.form_factors.timings["form_factors"] = ff_seconds;
  nlohmann::json run = {{"solver", solver}, {"tol", tol}, {"seed", seed}, {"threads", threads},
                        {"rays_per_patch", rays}, {"refine", refine}};
  a.result.metadata = result_metadata(a.result, a.scene, run);
  return a;
}

}  // namespace

Scene refined_scene(const Scene& scene, PatchSet patches) {
  // The refined patches keep their input face, hence its group.
  std::unordered_map<std::int32_t, std::int32_t> group_of_face;
  for (std::size_t i = 0; i < scene.patches.size(); ++i) group_of_face[scene.patches.face[i]] = scene.group[i];
  Scene out;
  out.path = scene.path;
  out.max_edge = scene.max_edge;
  out.max_area = scene.max_area;
  out.strict = scene.strict;
  out.orient = scene.orient;
  out.open_shells = scene.open_shells;
  out.scale = scene.scale;
  out.unit = scene.unit;
  out.length_unit = scene.length_unit;
  out.radiosity_unit = scene.radiosity_unit;
  out.two_sided = scene.two_sided;
  out.contact_cut = scene.contact_cut;
  out.cut = scene.cut;
  out.contact_regions = scene.contact_regions;
  out.groups = scene.groups;
  out.group_names = scene.group_names;
  out.patches = std::move(patches);
  out.group.resize(out.patches.size());
  for (std::size_t i = 0; i < out.patches.size(); ++i) out.group[i] = group_of_face.at(out.patches.face[i]);
  return out;
}

void bind_refinement(py::module_& m) {
  py::class_<AdaptiveResult>(m, "AdaptiveResult", R"doc(What solve_adaptive() returns.

scene: a Scene of the final (refined) patches, each keeping its input face, group and material (edit its rho and
  E to re-solve on the same mesh); form_factors: their FormFactors; result: their Result (B, ...; metadata holds
  the CLI's JSON "solution" and "refine" objects); jump: (N,) float64 the refinement criterion jump_i of the last solve
  (the .vtp's `jump` field); steps: one dict per solve (step, patches, marked, split, max_jump, method,
  iterations, form_factor_seconds, solve_seconds, refine_seconds, seconds: the JSON's refine.steps);
  stop_reason: "converged", "steps", "max-patches" or "solver".)doc")
      .def_readonly("scene", &AdaptiveResult::scene, "The Scene of the final (refined) patches, N of them.")
      .def_readonly("form_factors", &AdaptiveResult::form_factors, "The FormFactors of the final patches, (N, N).")
      .def_readonly("result", &AdaptiveResult::result,
                    "The Result of the last solve: B (N, 3) float64 in W per unit length squared, metadata, ...")
      .def_property_readonly(
          "jump", [](const AdaptiveResult& a) { return copy_array(a.jump); },
          "The refinement criterion jump_i of the last solve, (N,) float64 (a copy), in W per "
          "unit length squared.")
      .def_property_readonly(
          "steps",
          [](const AdaptiveResult& a) {
            py::list l;
            for (const RefineStep& s : a.steps) l.append(json_to_python(app::refine_step_json(s).dump()));
            return l;
          },
          "One dict per solve (a list): step, patches, marked, split, max_jump, method, iterations, "
          "form_factor_seconds, solve_seconds, refine_seconds, seconds (the JSON's refine.steps; times in s).")
      .def_readonly("stop_reason", &AdaptiveResult::stop_reason,
                    "Why the refinement stopped (str): \"converged\", \"steps\", \"max-patches\" or \"solver\".")
      .def("__repr__", [](const AdaptiveResult& a) {
        return "<radwalk.AdaptiveResult " + std::to_string(a.scene.patches.size()) + " patches after " +
               std::to_string(a.steps.size()) + " solves (" + a.stop_reason + ")>";
      });

  m.def(
      "solve_adaptive", &solve_adaptive_py, py::arg("scene"), py::arg("refine_tol") = 0.1, py::arg("steps") = 4,
      py::arg("max_patches") = 20000, py::arg("floor_fraction") = kDefaultRefineFloorFraction,
      py::arg("noise_z") = kDefaultRefineNoiseZ, py::arg("solver") = "auto", py::arg("tol") = 1e-10,
      py::arg("max_iterations") = 0, py::arg("rays") = 1000, py::arg("rays_per_area") = 0.0, py::arg("min_rays") = 16,
      py::arg("reciprocity") = false, py::arg("seed") = 1, py::arg("threads") = 0,
      R"doc(Adaptive patching: solve, split the patches whose radiosity jumps across an edge, re-solve: an AdaptiveResult.

As `radwalk solve SCENE --refine REFINE_TOL --refine-steps STEPS --max-patches MAX_PATCHES --refine-floor
FLOOR_FRACTION --refine-noise NOISE_Z --solver SOLVER --tol TOL --rays RAYS --seed SEED` (src/solve/
adaptive_refinement.h): every step estimates its own form factors with rays/rays_per_area/min_rays/seed
(reciprocity: --reciprocity) and solves with a deterministic solver ("auto", "direct", "jacobi",
"gauss-seidel", "southwell"); max_iterations 0 = the CLI's default. The same seed gives the CLI's B.
refine_tol, floor_fraction and noise_z are dimensionless: the relative jump of B across an edge that splits, the
floor of that difference as a fraction of the mean irradiance, and a number of form-factor standard errors;
rays_per_area is per mesh length unit squared; max_patches and steps are counts.
The scene passed in is not changed; the result's scene has the final N patches and its B is (N, 3) float64 in W
per unit length squared. The GIL is released during the whole refinement.
Raises radwalk.InputError for options out of range.)doc");
}

}  // namespace radwalk::python
