// radwalk.solve (the deterministic solvers) and the Result type every solver, walk and path tracer returns.
#include <nlohmann/json.hpp>

#include "bindings.h"
#include "core/parallel.h"
#include "interruptible.h"
#include "io/run_summary.h"
#include "core/timer.h"
#include "formfactor/form_factor_noise.h"
#include "solve/discretisation_error.h"
#include "solve/form_factor_error.h"
#include "solve/problem.h"
#include "solve/solve_radiosity.h"
#include "visibility/embree_visibility.h"

namespace radwalk::python {
namespace {

// An N x 3 field of the result, or None when the solver does not give it (e.g. B_se of a solve from a caller's F).
py::object rgb_or_none(py::object self, const PatchRgb& values) {
  if (values.size() == 0) return py::none();
  return rgb_view(values, self);
}

Result solve(const Scene& scene, const py::object& F, const std::string& solver, double tol, long max_iterations,
             long rays, std::uint64_t seed, long long threads_arg, int discretisation_directions) {
  if (discretisation_directions < 0)
    throw InputError("discretisation_directions must be >= 0 (0: not estimated), got " +
                     std::to_string(discretisation_directions));  // before any form factor is traced
  const int threads = check_run(scene, threads_arg);
  Result r;
  FormFactors sampling;
  SparseF f = form_factor_matrix(F, scene, rays, seed, threads, r.timings, &sampling);
  interruptible([&] {
    ThreadLimit limit(threads);
    SolveOptions o;
    o.solver = solver;
    o.tol = tol;
    o.max_iterations = max_iterations > 0 ? max_iterations : default_max_iterations(solver, scene.patches.size());
    const RadiosityProblem problem = make_problem(scene.patches, std::move(f));
    r.solution = solve_radiosity(problem, o);
    // B_se: the traced form factors' noise propagated through the solve (as the CLI's solve).
    if (has_noise_model(sampling) && r.solution.B.rows() == static_cast<Eigen::Index>(scene.patches.size())) {
      Timer timer;
      const EmbreeVisibility visibility(scene.patches);
      const FormFactorError error = form_factor_error(scene.patches, visibility, sampling, problem, r.solution.B);
      r.solution.B_se = error.standard_error;
      r.solution.info["sampling_factor_rays"] = error.calibration.factors.rays;
      r.solution.info["sampling_factor_emitter"] = error.calibration.factors.emitter;
      r.solution.info["coverage_factor"] = error.calibration.factors.coverage;
      r.timings["error_estimate"] = timer.seconds();
    }
    // As the CLI's solve with --seed: the seed F was traced with, when radwalk traced it.
    add_discretisation_error(r, scene, problem, discretisation_directions,
                             has_noise_model(sampling) ? sampling.options.seed : seed);
  });
  check_solved(r.solution);
  r.timings["solve"] = r.solution.seconds;
  nlohmann::json run = {{"solver", solver}, {"tol", tol}, {"seed", seed}, {"threads", threads}};
  r.metadata = result_metadata(r, scene, run);
  return r;
}

}  // namespace

void add_discretisation_error(Result& r, const Scene& scene, const RadiosityProblem& problem, int directions,
                              std::uint64_t seed) {
  if (directions < 0)
    throw InputError("discretisation_directions must be >= 0 (0: not estimated), got " + std::to_string(directions));
  if (directions == 0 || r.solution.status == SolveStatus::refused ||
      r.solution.B.rows() != static_cast<Eigen::Index>(scene.patches.size()) || !r.solution.B.allFinite())
    return;
  const EmbreeVisibility visibility(scene.patches);
  const DiscretisationError d = discretisation_error(scene.patches, visibility, problem, r.solution.B, directions, seed);
  r.solution.B_disc = d.standard_error;
  r.timings["discretisation_error"] = d.seconds;
}

std::string result_metadata(const Result& r, const Scene& scene, nlohmann::json run) {
  run["schema_version"] = RunSummary::kSchemaVersion;  // the key names of docs/json-schema.md
  run["solution"] = solution_json(r.solution);
  run["scene"] = scene.path;
  run["max_edge"] = scene.max_edge;
  run["patches"] = scene.patches.size();
  run["timings_s"] = r.timings;
  return run.dump();
}

void bind_solvers(py::module_& m) {
  py::class_<Result>(m, "Result", R"doc(What a solver, a random walk or the path tracer returns.

B (N, 3): radiosity per patch and channel (W per unit length squared); B_se (N, 3): its statistical standard error
(1 standard deviation: the walks' or path tracer's own noise, or for radwalk.solve from form factors radwalk traced,
their noise propagated through the solve, docs/accuracy.md; None for a caller's F); var, var_theory (N, 3):
per-walk variance and exact per-walk variance (Monte Carlo results; None where not computed). These are
read-only views of the C++ result (no copy) that keep it alive; np.array(r.B) gives a writable copy.
method, status ("converged" or "max-iterations"), message, iterations, residual, residual_history, walks_total,
steps, seconds, info: as the CLI's JSON "solution" object ("max-iterations" is not an exception: the CLI's exit
code 1; a solve that diverged or was refused raises radwalk.NumericalError with its message instead, where the
CLI exits 3).
timings: stage -> seconds; metadata: the JSON the CLI writes for the run (its "solution" object, options, timings_s).
fields: the per-patch fields of the CLI's CSV and .vtp for write_csv / write_vtp.)doc")
      .def_property_readonly(
          "B", [](py::object self) { return rgb_or_none(self, self.cast<const Result&>().solution.B); },
          "Radiosity (N, 3) float64 per patch and channel, W per unit length squared (read-only view).")
      .def_property_readonly(
          "B_se", [](py::object self) { return rgb_or_none(self, self.cast<const Result&>().solution.B_se); },
          "Standard error of B (N, 3) float64, W per unit length squared; None for a deterministic solve.")
      .def_property_readonly(
          "B_disc", [](py::object self) { return rgb_or_none(self, self.cast<const Result&>().solution.B_disc); },
          "Estimated discretisation error of B (N, 3) float64, W per unit length squared (1 standard deviation "
          "equivalent, docs/accuracy.md); None where not estimated.")
      .def_property_readonly(
          "B_err",
          [](py::object self) -> py::object {
            const Solution& s = self.cast<const Result&>().solution;
            if (!s.B_disc.size()) return rgb_or_none(self, s.B_se);
            return rgb_copy(total_error(s.B_se, s.B_disc));
          },
          "Total error sqrt(B_se^2 + B_disc^2) (N, 3) float64, W per unit length squared (a copy); B_se where "
          "B_disc is not estimated, None when neither is.")
      .def_property_readonly(
          "var", [](py::object self) { return rgb_or_none(self, self.cast<const Result&>().solution.var); },
          "Sample variance per walk or particle (N, 3) float64, (W per unit length squared)^2; None where not "
          "computed.")
      .def_property_readonly(
          "vov", [](py::object self) { return rgb_or_none(self, self.cast<const Result&>().solution.vov); },
          "Variance of the variance (N, 3) float64, dimensionless: the estimated relative variance of var's "
          "estimate (MCNP's VOV); B_se is reliable where it is below 0.1 (docs/path-tracer.md); the path "
          "tracer's, None elsewhere.")
      .def_property_readonly(
          "var_theory",
          [](py::object self) { return rgb_or_none(self, self.cast<const Result&>().solution.var_theory); },
          "Exact per-walk variance (N, 3) float64, (W per unit length squared)^2; None unless theory=True.")
      .def_property_readonly("method", [](const Result& r) { return r.solution.method; },
                             "The method that computed it (str): the solver, walk method or integrator name.")
      .def_property_readonly("status", [](const Result& r) { return std::string(to_string(r.solution.status)); },
                             "\"converged\" or \"max-iterations\" (str), as the CLI's JSON solution.status.")
      .def_property_readonly("message", [](const Result& r) { return r.solution.message; },
                             "The solver's one-line account of the run (str).")
      .def_property_readonly("iterations", [](const Result& r) { return r.solution.iterations; },
                             "Sweeps, shots or steps the solver made (int; 0 for a direct solve or a walk).")
      .def_property_readonly("residual", [](const Result& r) { return r.solution.residual; },
                             "The relative residual at the end (float; NaN where not computed), as the CLI's JSON "
                             "solution.residual.")
      .def_property_readonly("residual_history", [](const Result& r) {
        return copy_array(r.solution.residual_history);
      }, "The relative residual after each iteration (K,) float64 (a copy; empty for a direct solve).")
      .def_property_readonly("walks_total", [](const Result& r) { return r.solution.walks; },
                             "Walks or particles in all (int; 0 for a deterministic solve).")
      .def_property_readonly("steps", [](const Result& r) { return r.solution.steps; },
                             "Walk steps in all (int), the random walks' cost.")
      .def_property_readonly("seconds", [](const Result& r) { return r.solution.seconds; },
                             "Wall time of the solve (float, s).")
      .def_property_readonly("info", [](const Result& r) { return r.solution.info; },
                             "Solver-specific numbers (dict str -> float), as the CLI's JSON solution.info.")
      .def_readonly("timings", &Result::timings, "Stage -> wall time (dict str -> float, s), as the JSON's timings_s.")
      .def_property_readonly("metadata", [](const Result& r) { return json_to_python(r.metadata); },
                             "The JSON the CLI writes for the run (dict): its \"solution\" object, the options, "
                             "timings_s.")
      .def_property_readonly(
          "fields", [](py::object self) {
            // The names of cmd_solve / cmd_pathtrace: ParaView's B_var and B_var_theory, written var_* in the CSV.
            const Solution& s = self.cast<const Result&>().solution;
            py::dict d;
            d["B"] = rgb_view(s.B, self);
            if (s.B_se.size()) d["B_se"] = rgb_view(s.B_se, self);
            if (s.B_disc.size()) {
              d["B_disc"] = rgb_view(s.B_disc, self);
              d["B_err"] = rgb_copy(total_error(s.B_se, s.B_disc));
            }
            if (s.var.size()) d["B_var"] = py::make_tuple(rgb_view(s.var, self), "var");
            if (s.var_theory.size()) d["B_var_theory"] = py::make_tuple(rgb_view(s.var_theory, self), "var_theory");
            if (s.vov.size()) d["B_vov"] = py::make_tuple(rgb_view(s.vov, self), "vov");
            return d;
          },
          "The CLI's per-patch fields of this result as write_csv takes them (dict str -> (N, 3) float64 view, "
          "or (view, csv name)): B, B_se, B_disc, B_err, B_var, B_var_theory, B_vov where computed.")
      .def("__repr__", [](const Result& r) {
        return "<radwalk.Result " + r.solution.method + ": " + to_string(r.solution.status) + ", " +
               std::to_string(r.solution.B.rows()) + " patches>";
      });

  m.def("solve", &solve, py::arg("scene"), py::arg("F") = py::none(), py::arg("solver") = "auto",
        py::arg("tol") = 1e-10, py::arg("max_iterations") = 0, py::arg("rays") = 1000, py::arg("seed") = 1,
        py::arg("threads") = 0, py::arg("discretisation_directions") = 16,
        R"doc(Solves B = E + diag(rho) F B with a deterministic solver: a Result (B (N, 3) float64 in W per unit length
squared, residual, iterations, ...).

scene: a Scene, with rho and E as they are now (in-place edits count).
F: a FormFactors (form_factors), a scipy.sparse (N, N) matrix or (N, N) array (copied to float32 CSR), or None:
  estimated here with
  `rays` rays per patch and `seed`, as `radwalk solve SCENE --rays R --seed S` does.
solver: "auto" (direct up to a few thousand patches, else Gauss-Seidel), "direct", "jacobi", "gauss-seidel",
  "southwell" (the CLI's --solver); tol: relative residual to stop at (--tol);
  max_iterations: sweeps or shots, 0 = the CLI's default (10000, or 1000 x N shots for southwell).
threads: 0 = all cores. The GIL is released during the solve.
Result.B_se: for F traced by radwalk (None, or a FormFactors from form_factors) the form factors' noise
  propagated through the solve, as the CLI's B_se (docs/accuracy.md); None for a caller's matrix.
Result.B_disc: the estimated discretisation error (docs/accuracy.md), with `discretisation_directions` directions
  per point (the CLI's --discretisation-directions; 0: not estimated, None); Result.B_err the total.
Raises radwalk.InputError (a ValueError) for an unknown solver, bad options or bad values (rho outside [0, 1),
NaN, a malformed F, ...); radwalk.NumericalError when the solve diverged or was refused (its message).
For random walks use random_walk; for the continuous reference, pathtrace.)doc");
}

}  // namespace radwalk::python
