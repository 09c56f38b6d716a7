// radwalk.measure: one measurement M = <R, B>_A by any method of `radwalk measure` (walk/measure_by_method.h),
// with the response of a spec (apps/measure_response.h, as the CLI's --response) or of a numpy array of weights.
#include <limits>
#include <memory>

#include "apps/measure_response.h"
#include "formfactor/form_factor_noise.h"
#include "apps/run_metadata.h"
#include "bindings.h"
#include "core/timer.h"
#include "core/error.h"
#include "core/image.h"
#include "core/parallel.h"
#include "interruptible.h"
#include "io/run_summary.h"
#include "solve/problem.h"
#include "visibility/embree_visibility.h"
#include "walk/measure_by_method.h"

namespace radwalk::python {
namespace {

struct MeasureResult {
  Measurement measurement;
  Response response;
  std::map<std::string, double> timings;
  std::string metadata;  // JSON: the CLI's "measurement" object, with "importance" and "camera" where it has them
  bool has_disc = false;  // M_disc estimated (matrix-kernel methods with discretisation_directions > 0)
  Rgb M_disc = Rgb::Zero();
};

py::array_t<double> rgb_array(const Rgb& v) {
  py::array_t<double> a(3);
  for (int c = 0; c < 3; ++c) a.mutable_at(c) = v(c);
  return a;
}

Response response_of(const Scene& scene, const py::object& response, const std::vector<double>& camera, int width,
                     int height, nlohmann::json& metadata) {
  if (!camera.empty() && camera.size() != 10)
    throw InputError("camera takes 10 numbers: position (3), target (3), up (3), vertical fov in degrees");
  if (py::isinstance<py::str>(response)) {
    const std::string spec = response.cast<std::string>();
    if (spec == "camera")
      check_image_size(width, height, "width=" + std::to_string(width) + ", height=" + std::to_string(height));
    app::SceneCamera fitted;
    Response r = interruptible([&] {
      return app::measure_response(spec, scene.path, scene.patches, scene.group, scene.groups, camera, width,
                                   height, &fitted);
    });
    if (spec == "camera") metadata["camera"] = app::camera_json(fitted, scene.patches, width, height);
    return r;
  }
  const DoubleArray w = double_array(response, "response must be a spec (str) or an (N,) array of weights",
                                     "response weights must be real numbers, not");
  if (w.ndim() != 1) throw InputError("response weights must be an (N,) array, one weight per patch");
  Response r{Eigen::VectorXd(static_cast<Eigen::Index>(w.size())), "weights given in Python"};
  std::copy(w.data(), w.data() + w.size(), r.R.data());
  check_response(r, scene.patches.size());
  return r;
}

MeasureResult measure(const Scene& scene, const py::object& response, const py::object& F, const std::string& method,
                      long walks, const std::string& kernel, const std::string& survival, double survival_constant,
                      int importance_sweeps, double defensive, bool theory, const std::vector<double>& camera,
                      int width, int height, long rays, std::uint64_t seed, long long threads_arg,
                      int discretisation_directions) {
  if (discretisation_directions < 0)
    throw InputError("discretisation_directions must be >= 0 (0: not estimated), got " +
                     std::to_string(discretisation_directions));
  const int threads = check_run(scene, threads_arg);
  MeasureOptions o;
  o.method = method;
  o.walks = walks;
  o.walk.kernel = parse_walk_kernel(kernel);
  o.walk.survival.rule = parse_survival_rule(survival);
  o.walk.survival.constant = survival_constant;
  o.walk.seed = seed;
  o.importance_sweeps = importance_sweeps;
  o.defensive = defensive;
  o.theory = theory;
  MeasureResult r;
  nlohmann::json metadata;
  r.response = response_of(scene, response, camera, width, height, metadata);
  check_measure_options(o, scene.patches.size());  // before any form factor is traced, as the CLI
  const auto n = static_cast<Eigen::Index>(scene.patches.size());
  FormFactors sampling;  // how F was traced, for its noise in M_se (as the CLI's measure)
  SparseF f = measure_needs_form_factors(o) ? form_factor_matrix(F, scene, rays, seed, threads, r.timings, &sampling)
                                            : SparseF(n, n);
  nlohmann::json error_estimate, disc;
  interruptible([&] {
    ThreadLimit limit(threads);
    const RadiosityProblem problem = make_problem(scene.patches, std::move(f));
    std::unique_ptr<EmbreeVisibility> visibility;
    if (!measure_needs_form_factors(o)) visibility = std::make_unique<EmbreeVisibility>(scene.patches);
    r.measurement = measure_by_method(problem, &scene.patches, visibility.get(), r.response, o);
    if (measure_needs_form_factors(o)) {
      std::string covers;
      Timer timer;
      const PatchRgb B = app::discrete_solution(scene.patches, problem);
      double seconds = 0;
      error_estimate = app::add_form_factor_error(scene.patches, sampling, problem, B, r.response, r.measurement, covers);
      r.timings["error_estimate"] = timer.seconds();
      // As the CLI's measure: the seed F was traced with, when radwalk traced it.
      disc = app::add_measurement_discretisation_error(scene.patches, problem, B, r.response,
                                                       discretisation_directions,
                                                       has_noise_model(sampling) ? sampling.options.seed : seed,
                                                       r.M_disc, seconds);
      r.has_disc = !disc.is_null();
      if (r.has_disc) r.timings["discretisation_error"] = seconds;
    }
  });
  if (!error_estimate.is_null()) metadata["error_estimate"]["statistical"] = error_estimate;
  if (!disc.is_null()) {
    metadata["error_estimate"]["discretisation"] = disc;
    Rgb total;
    metadata["error_estimate"]["total"] = app::measurement_total_error(r.measurement.estimate.se, r.M_disc, total);
  } else if (!measure_needs_form_factors(o)) {
    metadata["error_estimate"]["discretisation"] = "not estimated: the ray kernel computes no B";
  }
  r.timings["measure"] = r.measurement.estimate.seconds;
  metadata["measurement"] = app::measurement_json(r.measurement, r.response, theory);
  if (is_importance_measure(method))
    metadata["importance"] = {{"source", r.measurement.importance_source},
                              {"sweeps", importance_sweeps},
                              {"defensive", r.measurement.defensive}};
  metadata["schema_version"] = RunSummary::kSchemaVersion;
  metadata["scene"] = scene.path;
  metadata["max_edge"] = scene.max_edge;
  metadata["patches"] = scene.patches.size();
  metadata["seed"] = seed;
  metadata["threads"] = threads;
  metadata["timings_s"] = r.timings;
  r.metadata = metadata.dump();
  return r;
}

}  // namespace

void bind_measure(py::module_& m) {
  py::class_<MeasureResult>(m, "Measurement",
                            R"doc(What measure() returns: M = <R, B>_A per channel and its error bar.

M, M_se, var_per_walk, var_per_walk_theory: (3,) arrays (per channel): the estimate (W for a response of weight
1; the mean pixel radiance for response="camera"), its standard error, the sample variance of one walk's score and
the exact one (NaN where not computed, +inf where infinite); deterministic methods have M_se = var_per_walk = 0.
walks_total (walks or particles in all; per channel for importance walks), steps, seconds, method, response (what
R is, in words), R (N,): the weights; deterministic; timings; metadata: the CLI's JSON "measurement" object (and
"importance", "camera" where the CLI writes them), same keys (docs/json-schema.md).)doc")
      .def_property_readonly(
          "M", [](const MeasureResult& r) { return rgb_array(r.measurement.estimate.M); },
          "The estimate M per channel, (3,) float64: W for a response of weight 1 (R_i dimensionless), the mean "
          "pixel radiance for response=\"camera\".")
      .def_property_readonly(
          "M_se", [](const MeasureResult& r) { return rgb_array(r.measurement.estimate.se); },
          "Standard error of M, (3,) float64, in M's unit (0 for a deterministic method).")
      .def_property_readonly(
          "M_disc",
          [](const MeasureResult& r) -> py::object {
            if (!r.has_disc) return py::none();
            return rgb_array(r.M_disc);
          },
          "The estimated discretisation error of M, (3,) float64, in M's unit (one standard deviation equivalent, "
          "docs/accuracy.md), or None where not estimated (ray-kernel walks, discretisation_directions=0).")
      .def_property_readonly(
          "var_per_walk", [](const MeasureResult& r) { return rgb_array(r.measurement.estimate.var); },
          "Sample variance of one walk's score, (3,) float64, in M's unit squared.")
      .def_property_readonly(
          "var_per_walk_theory", [](const MeasureResult& r) { return rgb_array(r.measurement.estimate.var_theory); },
          "The exact per-walk variance, (3,) float64, in M's unit squared (NaN where not "
          "computed, +inf where infinite).")
      .def_property_readonly(
          "walks_total", [](const MeasureResult& r) { return r.measurement.estimate.walks; },
          "Walks or particles in all (int; per channel for importance walks).")
      .def_property_readonly(
          "steps", [](const MeasureResult& r) { return r.measurement.estimate.counters.steps; },
          "Walk steps in all (int).")
      .def_property_readonly(
          "seconds", [](const MeasureResult& r) { return r.measurement.estimate.seconds; },
          "Wall time of the measurement (float, s).")
      .def_property_readonly(
          "method", [](const MeasureResult& r) { return r.measurement.estimate.method; },
          "The method (str), one of measure_methods().")
      .def_property_readonly(
          "deterministic", [](const MeasureResult& r) { return r.measurement.deterministic; },
          "Whether the method is deterministic (bool: direct, adjoint-direct).")
      .def_property_readonly(
          "response", [](const MeasureResult& r) { return r.response.what; }, "What R is, in words (str).")
      .def_property_readonly(
          "R",
          [](const MeasureResult& r) {
            return py::array_t<double>(r.response.R.size(), r.response.R.data());  // a copy of the Eigen vector
          },
          "The response weights R_i, (N,) float64 (a copy), dimensionless.")
      .def_readonly("timings", &MeasureResult::timings, "Stage -> wall time (dict str -> float, s).")
      .def_property_readonly(
          "metadata", [](const MeasureResult& r) { return json_to_python(r.metadata); },
          "The CLI's JSON \"measurement\" object (dict), with \"importance\" and \"camera\" "
          "where the CLI writes them (docs/json-schema.md).")
      .def("__repr__", [](const MeasureResult& r) {
        return "<radwalk.Measurement " + r.measurement.estimate.method + " over " + r.response.what + ">";
      });

  m.def("measure_methods", &measure_method_names,
        "The methods of measure() (a list of str): direct, adjoint-direct, importance-gather, importance-shoot and "
        "the walk methods.");
  m.def("measure", &measure, py::arg("scene"), py::arg("response"), py::arg("F") = py::none(),
        py::arg("method") = "adjoint-direct", py::arg("walks") = 100000, py::arg("kernel") = "matrix",
        py::arg("survival") = "analog", py::arg("survival_constant") = 0.5, py::arg("importance_sweeps") = -1,
        py::arg("defensive") = -1.0, py::arg("theory") = false, py::arg("camera") = std::vector<double>{},
        py::arg("width") = 256, py::arg("height") = 256, py::arg("rays") = 1000, py::arg("seed") = 1,
        py::arg("threads") = 0, py::arg("discretisation_directions") = 16,
        R"doc(One measurement M = <R, B>_A = sum_i A_i R_i B_i per channel, with its standard error: a Measurement.

As `radwalk measure SCENE --response RESPONSE --method METHOD --walks WALKS ...` (same seed, same M):
response: a spec as the CLI's --response ("patches:0,3", "material:white", "group:desk", "csv:FILE:COLUMN",
  "camera": the mean pixel radiance of the view of `camera` (10 numbers as pathtrace's, empty: the scene's
  own), width x height pixels) or an (N,) float array of dimensionless weights R_i >= 0.
method: one of measure_methods(): "direct" (<R, B> from the LU solve), "adjoint-direct" (<Y, E> from the adjoint
  solve), a walk method of walk_methods() (gathering methods walk from the sensor, shooting ones from the
  sources; kernel "matrix" or "ray", survival as random_walk), "importance-gather" / "importance-shoot"
  (importance-driven walks; importance_sweeps -1: the exact importance (zero variance), K >= 0: K Jacobi sweeps;
  defensive: the analog fraction alpha, -1: 0 exact, 0.1 swept).
walks: walks or particles in all (per channel for the importance walks); theory: also the exact per-walk variance
  (matrix kernel, N <= 2000). F: a FormFactors, a scipy.sparse (N, N) matrix, or None (estimated with rays and
  seed). Returns M, M_se as (3,) float64 arrays (W for weights of 1, the patches' B in W per unit length squared
  times their areas).
Raises radwalk.InputError for a bad response, method or option (the CLI's message).)doc");
}

}  // namespace radwalk::python
