// radwalk.random_walk, radwalk.compare and radwalk.exact_variance: the discrete random-walk estimators.
// The method names are those of the one method table (walk/walk_method.h, radwalk.walk_methods()).
#include <limits>
#include <memory>
#include <optional>

#include "bindings.h"
#include "core/error.h"
#include "core/parallel.h"
#include "interruptible.h"
#include "core/timer.h"
#include "formfactor/form_factor_noise.h"
#include "solve/form_factor_error.h"
#include "solve/problem.h"
#include "solve/solve_radiosity.h"
#include "visibility/embree_visibility.h"
#include "walk/random_walk_solver.h"
#include "walk/walk_compare.h"
#include "walk/walk_method.h"
#include "walk/walk_variance.h"

namespace radwalk::python {
namespace {

// The method random_walk, compare and exact_variance use when none is named (the CLI's default too).
constexpr WalkMethod kDefaultMethod = WalkMethod::gather_collision;

// The per-method part of a comparison: its summary and its per-patch arrays (NaN where it estimated nothing).
struct EstimatorComparison {
  CompareSummary summary;
  PatchRgb mean, var, var_se, var_theory, z;
};

struct Comparison {
  PatchRgb B_reference;
  std::vector<std::string> names;
  std::vector<EstimatorComparison> estimators;
  std::vector<CompareRow> rows;
  std::map<std::string, double> timings;
};

WalkOptions walk_options(const std::string& method, const std::string& kernel, long walks_per_patch, long particles,
                         std::uint64_t seed, const std::string& survival, double survival_constant,
                         const std::vector<int>& patches) {
  WalkOptions w;
  w.method = parse_walk_method(method);
  w.kernel = parse_walk_kernel(kernel);
  w.walks_per_patch = walks_per_patch;
  w.particles = particles;
  w.seed = seed;
  w.survival.rule = parse_survival_rule(survival);
  w.survival.constant = survival_constant;
  w.patches = patches;
  return w;
}

// F for the matrix kernel (form_factor_matrix); the ray kernel stores none (an empty N x N F, as the CLI's).
SparseF walk_form_factors(const py::object& F, const Scene& scene, WalkKernel kernel, long rays, std::uint64_t seed,
                          int threads, std::map<std::string, double>& timings, FormFactors* sampling = nullptr) {
  const auto n = static_cast<Eigen::Index>(scene.patches.size());
  if (kernel == WalkKernel::ray) return SparseF(n, n);
  return form_factor_matrix(F, scene, rays, seed, threads, timings, sampling);
}

Result random_walk(const Scene& scene, const py::object& F, const std::string& method, const std::string& kernel,
                   std::optional<long> walks_per_patch, std::optional<long> particles, std::uint64_t seed,
                   const std::string& survival, double survival_constant, bool theory,
                   const std::vector<int>& patches, long rays, long long threads_arg, bool progress,
                   bool control_variate, const std::string& sampler, int replicates, bool direct_light,
                   long shadow_rays, int discretisation_directions) {
  if (discretisation_directions < 0)
    throw InputError("discretisation_directions must be >= 0 (0: not estimated), got " +
                     std::to_string(discretisation_directions));
  const int threads = check_run(scene, threads_arg);
  WalkOptions w = walk_options(method, kernel, walks_per_patch.value_or(1000), particles.value_or(1000), seed,
                               survival, survival_constant, patches);
  // The count the method does not read is refused, as the CLI refuses --particles with gathering walks.
  if (is_gathering(w.method) && particles)
    throw InputError("particles counts shooting particles; gathering walks (" + method + ") take walks_per_patch");
  if (!is_gathering(w.method) && walks_per_patch)
    throw InputError("walks_per_patch counts gathering walks; shooting walks (" + method + ") take particles");
  w.theory = theory;
  w.progress = progress;
  w.control_variate = control_variate;
  w.sampler = parse_walk_sampler(sampler);
  w.replicates = replicates;
  w.direct_light = direct_light;
  w.shadow_rays = shadow_rays;
  check_walk_options(w, scene.patches.size());  // before any form factor is traced, as the CLI
  Result r;
  FormFactors sampling;  // how F was traced: its noise joins B_se on the matrix kernel, as in the CLI
  SparseF f = walk_form_factors(F, scene, w.kernel, rays, seed, threads, r.timings, &sampling);
  interruptible([&] {
    ThreadLimit limit(threads);
    const RadiosityProblem problem = make_problem(scene.patches, std::move(f));
    std::unique_ptr<EmbreeVisibility> visibility;
    if (w.kernel == WalkKernel::ray) visibility = std::make_unique<EmbreeVisibility>(scene.patches);
    r.solution = solve_random_walk(problem, &scene.patches, visibility.get(), w);
    const auto N = static_cast<Eigen::Index>(scene.patches.size());
    if (has_noise_model(sampling) && r.solution.B.rows() == N && r.solution.B_se.rows() == N) {
      Timer timer;
      const EmbreeVisibility traced(scene.patches);
      const FormFactorError error = form_factor_error(scene.patches, traced, sampling, problem, r.solution.B);
      r.solution.B_se = combined_standard_error(r.solution.B_se, error.standard_error);
      r.timings["error_estimate"] = timer.seconds();
    }
    add_discretisation_error(r, scene, problem, discretisation_directions, seed);  // as the CLI's solve
  });
  check_solved(r.solution);
  r.timings["solve"] = r.solution.seconds;
  const WalkMethodRow& row = method_row(w.method);
  nlohmann::json run = {{"solver", "random-walk"},
                        {"method", std::string(row.name)},
                        {"walk", std::string(direction_name(row.direction))},
                        {"estimator", std::string(row.estimator)},
                        {"kernel", std::string(kernel_name(w.kernel))},
                        {"survival", std::string(survival_name(w.survival.rule))},
                        {"seed", seed},
                        {"threads", threads},
                        {"walks_total", total_walks(w, scene.patches.size())}};
  if (is_gathering(w.method))
    run["walks_per_patch"] = w.walks_per_patch;
  else
    run["particles"] = w.particles;
  r.metadata = result_metadata(r, scene, run);
  return r;
}

Comparison compare(const Scene& scene, const py::object& F, const std::optional<std::vector<std::string>>& methods,
                   int runs, long walks_per_patch, const std::string& kernel, std::uint64_t seed,
                   const std::string& survival, double survival_constant, bool theory,
                   const std::vector<int>& patches, long rays, long long threads_arg, bool progress) {
  const int threads = check_run(scene, threads_arg);
  CompareOptions o;
  if (methods) {
    o.methods.clear();
    for (const std::string& name : *methods) o.methods.push_back(parse_walk_method(name));
  }
  o.runs = runs;
  o.walk = walk_options(std::string(method_name(kDefaultMethod)), kernel, walks_per_patch, 1000, seed, survival,
                        survival_constant, patches);
  o.theory = theory;
  o.progress = progress;
  check_compare_options(o, scene.patches.size());
  Comparison c;
  SparseF f = form_factor_matrix(F, scene, rays, seed, threads, c.timings);  // the reference needs F either way
  CompareResult result;
  interruptible([&] {
    ThreadLimit limit(threads);
    const RadiosityProblem problem = make_problem(scene.patches, std::move(f));
    // The reference, as `radwalk compare`: the direct solve of the same discrete system.
    SolveOptions direct;
    direct.solver = "direct";
    const Solution reference = solve_radiosity(problem, direct);
    check_solved(reference);
    c.timings["reference solve"] = reference.seconds;
    c.B_reference = reference.B;
    std::unique_ptr<EmbreeVisibility> visibility;
    if (o.walk.kernel == WalkKernel::ray) visibility = std::make_unique<EmbreeVisibility>(scene.patches);
    result = compare_random_walks(problem, &scene.patches, visibility.get(), o, reference.B);
  });
  const auto n = static_cast<Eigen::Index>(scene.patches.size());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  double walks_seconds = 0;
  for (const CompareSummary& s : result.summary) {
    EstimatorComparison e;
    e.summary = s;
    e.mean = e.var = e.var_se = e.var_theory = e.z = PatchRgb::Constant(n, 3, nan);
    c.names.emplace_back(method_name(s.method));
    c.estimators.push_back(std::move(e));
    walks_seconds += s.seconds;
  }
  for (const CompareRow& row : result.rows)
    for (std::size_t k = 0; k < c.estimators.size(); ++k)
      if (c.estimators[k].summary.method == row.method) {
        c.estimators[k].mean(row.patch, row.channel) = row.mean;
        c.estimators[k].var(row.patch, row.channel) = row.var;
        c.estimators[k].var_se(row.patch, row.channel) = row.var_se;
        c.estimators[k].var_theory(row.patch, row.channel) = row.var_theory;
        c.estimators[k].z(row.patch, row.channel) = row.z;
      }
  c.timings["walks"] = walks_seconds;
  c.rows = std::move(result.rows);
  return c;
}

py::array_t<double> exact_variance(const Scene& scene, const py::object& F, const std::string& method,
                                   const std::string& survival, double survival_constant, long rays,
                                   std::uint64_t seed, long long threads_arg) {
  const int threads = check_run(scene, threads_arg);
  WalkOptions w = walk_options(method, "matrix", 1000, 1000, seed, survival, survival_constant, {});
  std::map<std::string, double> timings;
  SparseF f = form_factor_matrix(F, scene, rays, seed, threads, timings);
  const PatchRgb var = interruptible([&] {
    ThreadLimit limit(threads);
    const RadiosityProblem problem = make_problem(scene.patches, std::move(f));
    return theoretical_variance(problem, w, dense_radiosity(problem));
  });
  py::array_t<double> out({static_cast<py::ssize_t>(var.rows()), py::ssize_t{3}});
  std::copy(var.data(), var.data() + var.size(), out.mutable_data());
  return out;
}

}  // namespace

void bind_walks(py::module_& m) {
  // The method names in the docstrings come from the method table (walk/walk_method.h), never spelled here.
  const auto methods_of = [](WalkDirection direction) {
    std::string list;
    for (const WalkMethodRow& row : kWalkMethods)
      if (row.direction == direction) list += (list.empty() ? "\"" : ", \"") + std::string(row.name) + "\"";
    return list;
  };
  static const std::string random_walk_doc = std::string(
      R"doc(Solves the radiosity system by discrete random walks: a Result with B, B_se, var (and var_theory), each (N, 3)
float64 (B and B_se in W per unit length squared, the variances in its square).

method: a name of radwalk.walk_methods() (the one table, src/walk/walk_method.h): )doc" +
      methods_of(WalkDirection::gather) + R"doc( (walks from each
  estimated patch, walks_per_patch of them, default 1000) or )doc" +
      methods_of(WalkDirection::shoot) + R"doc(
  (particles from the emitters, `particles` in total, default 1000); the count the method does not read is
  refused (InputError), as in the CLI;
  the CLI's --walk D --estimator E is method "D-E".
kernel: "matrix" (stored F, alias tables) or "ray" (Embree traces every step, F is not used or estimated).
F: a FormFactors, a scipy.sparse (N, N) matrix, or None (estimated with `rays` and `seed`, as the CLI).
survival: "analog", "max" or "constant" (with survival_constant), the roulette rule; theory: also the exact
  per-walk variance var_theory (matrix kernel, N <= 2000); patches: gathering only, the patches to estimate
  (a list of int; empty: all; the others are NaN); seed: as the CLI's --seed (same seed, same B for any thread count).
control_variate: gathering, matrix kernel: walk B - c from the shifted source and add the constant c back, as the
  CLI's --control-variate (docs/theory/control_variate.md).
sampler, replicates, direct_light, shadow_rays: shooting, as the CLI's --sampler, --replicates, --direct-light
  and --shadow-rays (src/walk/walk_options.h): sampler "random" (i.i.d. particles), "sobol" (stratified
  emission, randomised Sobol first rays) or "jacobi" (stochastic Jacobi, )doc" +
      std::string(method_name(WalkMethod::shoot_collision)) + R"doc( only); with sobol or
  jacobi, `replicates` independent randomisations (>= 2) give B_se from their spread, and direct_light computes
  the first bounce apart (ray kernel: point-to-polygon form factors x visibility with shadow_rays samples per
  receiving patch, 0: particles / (2 N); matrix kernel: exact from F). The random sampler reads neither
  replicates nor shadow_rays, and direct_light needs sobol or jacobi (InputError, as the CLI).
discretisation_directions: Result.B_disc, the estimated discretisation error, with that many directions per point
  (the CLI's --discretisation-directions; 0: not estimated, None); Result.B_err the total.
Raises radwalk.InputError for an unknown name (with the valid ones and the nearest) or a bad count;
radwalk.NumericalError when the walks refuse the system (spectral radius >= 1), with the walks' message.)doc");
  py::class_<EstimatorComparison>(m, "EstimatorComparison",
                                  R"doc(One method of a compare(): per-patch arrays and its summary.

mean, var, var_se, var_theory, z (N, 3): average of the runs' estimates, per-walk variance averaged over the runs,
its standard error from the spread of the runs' variances (NaN for one run), exact
per-walk variance (NaN where not computable), (mean - B_reference) / sqrt(var / walks); NaN for patches the method
did not estimate. Summary (walk/walk_compare.h), named as the CLI's JSON "estimators" (docs/json-schema.md):
runs, walks_total (over all runs and estimated patches), walks_per_estimate (behind each patch's pooled estimate:
runs x walks_per_patch gathering, runs x particles shooting), steps, seconds, mean_abs_z (about 0.80 for an
unbiased method with right error bars), max_abs_z, var_over_theory (mean var / var_theory, about 1),
spread_over_se (run-to-run standard deviation over the predicted standard error, about 1; NaN for one run),
mean_var_per_walk, efficiency = walks_per_estimate / (mean_var_per_walk x seconds).)doc")
      .def_property_readonly(
          "method", [](const EstimatorComparison& e) { return std::string(method_name(e.summary.method)); },
          "The method's name (str), from radwalk.walk_methods().")
      .def_property_readonly(
          "mean", [](py::object self) { return rgb_view(self.cast<const EstimatorComparison&>().mean, self); },
          "Average of the runs' estimates (N, 3) float64, W per unit length squared; NaN where not estimated.")
      .def_property_readonly(
          "var", [](py::object self) { return rgb_view(self.cast<const EstimatorComparison&>().var, self); },
          "Per-walk variance averaged over the runs (N, 3) float64, (W per unit length squared)^2.")
      .def_property_readonly(
          "var_se", [](py::object self) { return rgb_view(self.cast<const EstimatorComparison&>().var_se, self); },
          "Standard error of var (N, 3) float64 from the spread of the runs' variances (NaN for one run).")
      .def_property_readonly(
          "var_theory",
          [](py::object self) { return rgb_view(self.cast<const EstimatorComparison&>().var_theory, self); },
          "Exact per-walk variance (N, 3) float64, (W per unit length squared)^2 (NaN where not computable).")
      .def_property_readonly(
          "z", [](py::object self) { return rgb_view(self.cast<const EstimatorComparison&>().z, self); },
          "(mean - B_reference) / sqrt(var / walks) (N, 3) float64, dimensionless.")
      .def_property_readonly(
          "runs", [](const EstimatorComparison& e) { return e.summary.runs; },
          "The number of runs made (int), run r with seed + r.")
      .def_property_readonly(
          "walks_total", [](const EstimatorComparison& e) { return e.summary.walks; },
          "Walks or particles over all runs and estimated patches (int).")
      .def_property_readonly(
          "walks_per_estimate", [](const EstimatorComparison& e) { return e.summary.walks_per_estimate; },
          "Walks behind each patch's pooled estimate (int): runs x walks_per_patch or runs x particles.")
      .def_property_readonly(
          "steps", [](const EstimatorComparison& e) { return e.summary.steps; }, "Walk steps over all runs (int).")
      .def_property_readonly(
          "seconds", [](const EstimatorComparison& e) { return e.summary.seconds; },
          "Wall time over all runs (float, s).")
      .def_property_readonly(
          "mean_abs_z", [](const EstimatorComparison& e) { return e.summary.mean_abs_z; },
          "Mean |z| over the estimated patches and channels (float; about 0.80 when unbiased with right error bars).")
      .def_property_readonly(
          "max_abs_z", [](const EstimatorComparison& e) { return e.summary.max_abs_z; }, "Largest |z| (float).")
      .def_property_readonly(
          "var_over_theory", [](const EstimatorComparison& e) { return e.summary.var_ratio; },
          "Mean var / var_theory (float; about 1).")
      .def_property_readonly(
          "spread_over_se", [](const EstimatorComparison& e) { return e.summary.spread_ratio; },
          "Run-to-run standard deviation over the predicted standard error (float; about 1, NaN for one run).")
      .def_property_readonly(
          "mean_var_per_walk", [](const EstimatorComparison& e) { return e.summary.mean_var; },
          "Mean per-walk variance over patches and channels (float, (W per unit length squared)^2).")
      .def_property_readonly(
          "efficiency", [](const EstimatorComparison& e) { return e.summary.efficiency; },
          "walks_per_estimate / (mean_var_per_walk x seconds) (float, 1 / ((W per unit length squared)^2 s)).")
      .def("__repr__", [](const EstimatorComparison& e) {
        return "<radwalk.EstimatorComparison " + std::string(method_name(e.summary.method)) + ">";
      });

  py::class_<Comparison>(m, "Comparison", R"doc(What compare() returns.

B_reference (N, 3): the direct solve the z-scores are measured against; estimators: dict method name ->
EstimatorComparison, in the order asked; summary: the CLI's text table; rows: the CLI's long-format CSV as a
dict of numpy columns (patch, estimator, channel 0..2, mean, var, var_theory, z, walks, steps, seconds,
efficiency), e.g. pandas.DataFrame(c.rows); timings: stage -> seconds.)doc")
      .def_property_readonly(
          "B_reference", [](py::object self) { return rgb_view(self.cast<const Comparison&>().B_reference, self); },
          "The direct solve of the same F (N, 3) float64, W per unit length squared.")
      .def_property_readonly(
          "estimators",
          [](py::object self) {
            const Comparison& c = self.cast<const Comparison&>();
            py::dict d;
            for (std::size_t k = 0; k < c.names.size(); ++k)
              d[py::str(c.names[k])] = py::cast(&c.estimators[k], py::return_value_policy::reference_internal, self);
            return d;
          },
          "Method name -> EstimatorComparison (dict), in the order asked.")
      .def_property_readonly(
          "summary",
          [](const Comparison& c) {
            std::vector<CompareSummary> s;
            for (const auto& e : c.estimators) s.push_back(e.summary);
            return format_compare_summary(s);
          },
          "The CLI's text table of the comparison (str).")
      .def_property_readonly(
          "rows",
          [](const Comparison& c) {
            const std::size_t n = c.rows.size();
            py::array_t<std::int64_t> patch(n), channel(n), walks(n), steps(n);
            py::array_t<double> mean(n), var(n), var_se(n), var_theory(n), z(n), seconds(n), efficiency(n);
            py::list estimator;
            for (std::size_t i = 0; i < n; ++i) {
              const CompareRow& r = c.rows[i];
              patch.mutable_at(i) = r.patch;
              channel.mutable_at(i) = r.channel;
              walks.mutable_at(i) = r.walks;
              steps.mutable_at(i) = r.steps;
              mean.mutable_at(i) = r.mean;
              var.mutable_at(i) = r.var;
              var_se.mutable_at(i) = r.var_se;
              var_theory.mutable_at(i) = r.var_theory;
              z.mutable_at(i) = r.z;
              seconds.mutable_at(i) = r.seconds;
              efficiency.mutable_at(i) = r.efficiency;
              estimator.append(py::str(std::string(method_name(r.method))));
            }
            py::dict d;
            d["patch"] = patch;
            d["estimator"] = estimator;
            d["channel"] = channel;
            d["mean"] = mean;
            d["var"] = var;
            d["var_se"] = var_se;
            d["var_theory"] = var_theory;
            d["z"] = z;
            d["walks"] = walks;
            d["steps"] = steps;
            d["seconds"] = seconds;
            d["efficiency"] = efficiency;
            return d;
          },
          "The CLI's long-format CSV as columns (dict str -> (R,) array, R = patches x channels x methods): patch, "
          "channel, walks, steps int64; estimator a list of str; mean, var, var_se, var_theory, z, seconds, "
          "efficiency float64 (units as EstimatorComparison's).")
      .def_readonly("timings", &Comparison::timings, "Stage -> wall time (dict str -> float, s).");

  m.def("random_walk", &random_walk, py::arg("scene"), py::arg("F") = py::none(),
        py::arg("method") = std::string(method_name(kDefaultMethod)), py::arg("kernel") = "matrix",
        py::arg("walks_per_patch") = py::none(), py::arg("particles") = py::none(), py::arg("seed") = 1,
        py::arg("survival") = "analog", py::arg("survival_constant") = 0.5, py::arg("theory") = false,
        py::arg("patches") = std::vector<int>{}, py::arg("rays") = 1000, py::arg("threads") = 0,
        py::arg("progress") = false, py::arg("control_variate") = false,
        py::arg("sampler") = std::string(sampler_name(WalkOptions{}.sampler)),
        py::arg("replicates") = WalkOptions{}.replicates, py::arg("direct_light") = WalkOptions{}.direct_light,
        py::arg("shadow_rays") = WalkOptions{}.shadow_rays, py::arg("discretisation_directions") = 16,
        random_walk_doc.c_str());

  m.def("compare", &compare, py::arg("scene"), py::arg("F") = py::none(), py::arg("methods") = py::none(),
        py::arg("runs") = 5, py::arg("walks_per_patch") = 1000, py::arg("kernel") = "matrix", py::arg("seed") = 1,
        py::arg("survival") = "analog", py::arg("survival_constant") = 0.5, py::arg("theory") = true,
        py::arg("patches") = std::vector<int>{}, py::arg("rays") = 1000, py::arg("threads") = 0,
        py::arg("progress") = false,
        R"doc(Runs random-walk methods `runs` times each on one budget and compares them: a Comparison.

As `radwalk compare`: the budget is walks_per_patch walks per estimated patch for gathering methods and the same
total as particles for shooting ones; run r uses seed + r; the reference is the direct solve of the same F.
methods: names of radwalk.walk_methods() (None: all six); the other options as random_walk.
patches: the patch indices to estimate (a list of int; empty: all); F as random_walk's (None, a FormFactors or a
scipy.sparse (N, N) matrix).)doc");

  m.def("exact_variance", &exact_variance, py::arg("scene"), py::arg("F") = py::none(),
        py::arg("method") = std::string(method_name(kDefaultMethod)), py::arg("survival") = "analog",
        py::arg("survival_constant") = 0.5, py::arg("rays") = 1000, py::arg("seed") = 1, py::arg("threads") = 0,
        R"doc(The exact per-walk (gathering) or per-particle (shooting) variance of a method with the matrix kernel.

An (N, 3) float64 array in (W per unit length squared)^2, +inf where the variance is infinite (spectral radius of
K >= 1); dense algebra, N <= 2000 (walk/walk_variance.h). The standard error of a run of n walks is
sqrt(var / n). F: None (estimated with `rays` and `seed`), a FormFactors or a scipy.sparse (N, N) matrix.)doc");
}

}  // namespace radwalk::python
