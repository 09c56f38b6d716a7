#include "walk/measure_by_method.h"

#include <algorithm>
#include <optional>

#include "core/did_you_mean.h"
#include "core/error.h"
#include "core/moments.h"
#include "core/timer.h"
#include "solve/direct_solver.h"
#include "walk/walk_method.h"

namespace radwalk {
namespace {

WalkOptions walk_options(const MeasureOptions& o) {
  WalkOptions w = o.walk;
  w.method = parse_walk_method(o.method);
  w.walks_per_patch = w.particles = o.walks;
  return w;
}

PatchRgb direct_B(const RadiosityProblem& problem) {
  const Solution s = DirectSolver(problem).solve(problem);
  if (s.status != SolveStatus::converged) throw NumericalError(s.message);
  return s.B;
}

PatchRgb adjoint_Y(const RadiosityProblem& problem, const Response& response) {
  const Solution Y = solve_adjoint_direct(problem, response);
  if (Y.status != SolveStatus::converged) throw NumericalError(Y.message);
  return Y.B;
}

// Every method's one rule for a result that does not fit a double: a measurement whose M, standard error or
// per-walk sample variance is not finite is refused (NumericalError, naming the quantity, the method and the
// response), never printed as inf or NaN. The exact per-walk variance is not checked: it is legitimately infinite
// when the second-moment system diverges, and is reported as such.
void refuse_overflow(const MeasureEstimate& est, const std::string& method, const Response& response) {
  const auto check = [&](const Rgb& v, const std::string& what) {
    if (v.allFinite()) return;
    throw NumericalError("--method " + method + ": " + what + " over " + response.what +
                         " overflows a double (largest response weight " + number_text(response.R.maxCoeff()) +
                         "): scale the response weights or the emission down");
  };
  check(est.M, "the measurement M = <R, B>_A");
  check(est.se, "the standard error of M");
  check(est.var, "the per-walk variance of M");
}

}  // namespace

std::vector<std::string> measure_method_names() {
  std::vector<std::string> names = {"direct", "adjoint-direct", "importance-gather", "importance-shoot"};
  for (const std::string& m : walk_method_names()) names.push_back(m);
  return names;
}

bool is_deterministic_measure(const std::string& method) { return method == "direct" || method == "adjoint-direct"; }

bool is_importance_measure(const std::string& method) {
  return method == "importance-gather" || method == "importance-shoot";
}

void check_measure_options(const MeasureOptions& o, std::size_t patch_count) {
  const bool deterministic = is_deterministic_measure(o.method), importance = is_importance_measure(o.method);
  if (!deterministic && !importance) {
    const std::vector<std::string> names = measure_method_names();
    if (std::find(names.begin(), names.end(), o.method) == names.end()) {
      std::string list;
      for (const std::string& m : names) list += (list.empty() ? "" : ", ") + m;
      throw InputError("--method: unknown value '" + printable(o.method) + "'" + did_you_mean(o.method, names) +
                       "; choose from " + list);
    }
    check_walk_options(walk_options(o), patch_count);
  } else if (o.walks < 1 && importance) {
    throw InputError("--walks must be at least 1 (got " + std::to_string(o.walks) + ")");
  }
  if ((deterministic || importance) && o.walk.kernel == WalkKernel::ray)
    throw InputError("kernel ray: --method " + o.method + " does not walk on a kernel (it uses the matrix of form "
                     "factors); use a walk method (e.g. --method " +
                     std::string(method_name(WalkMethod::gather_expected_value)) + ") for the ray kernel");
  const bool needs_lu = deterministic || (importance && o.importance_sweeps < 0);
  if (needs_lu && patch_count > static_cast<std::size_t>(kDenseMaxPatches))
    throw InputError("--method " + o.method + (importance ? " with the exact importance" : "") + " needs an LU of " +
                     std::to_string(patch_count) + " patches (at most " + std::to_string(kDenseMaxPatches) +
                     "): use a walk method (e.g. --method " + std::string(method_name(WalkMethod::gather_expected_value)) +
                     " --kernel ray, no F stored) or " +
                     (importance ? "--importance-sweeps K" : "importance walks with --importance-sweeps K"));
}

bool measure_needs_form_factors(const MeasureOptions& o) {
  return is_deterministic_measure(o.method) || is_importance_measure(o.method) || o.walk.kernel != WalkKernel::ray;
}

namespace {

Measurement measure_unscaled(const RadiosityProblem& problem, const PatchSet* patches, const Visibility* visibility,
                             const Response& response, const MeasureOptions& o) {
  Measurement m;
  MeasureEstimate& est = m.estimate;
  m.deterministic = is_deterministic_measure(o.method);
  Timer timer;
  if (o.method == "direct") {
    est.M = measure(problem.area, response.R, direct_B(problem));
    est.se = est.var = Rgb::Zero();
  } else if (o.method == "adjoint-direct") {
    est.M = adjoint_measure(problem.area, adjoint_Y(problem, response), problem.E);
    est.se = est.var = Rgb::Zero();
  } else if (is_importance_measure(o.method)) {
    const bool sensor = o.method == "importance-gather";
    const bool exact = o.importance_sweeps < 0;
    const PatchRgb g = exact ? (sensor ? direct_B(problem) : adjoint_Y(problem, response))
                             : (sensor ? partial_radiosity(problem, o.importance_sweeps)
                                       : partial_importance(problem, response, o.importance_sweeps));
    m.defensive = o.defensive >= 0 ? o.defensive : exact ? 0.0 : 0.1;
    m.importance_source = exact ? "direct" : "jacobi";
    est = measure_importance(problem, response,
                             sensor ? ImportanceDirection::from_sensor : ImportanceDirection::from_sources, g,
                             m.defensive, o.walks, o.walk.seed, o.theory);
  } else {
    const bool ray = o.walk.kernel == WalkKernel::ray;
    est = measure_random_walk(problem, ray ? patches : nullptr, ray ? visibility : nullptr, walk_options(o), response,
                              o.walks, o.theory && !ray);
  }
  if (m.deterministic) est.seconds = timer.seconds();
  est.method = o.method;
  return m;
}

}  // namespace

// Scale before squaring (core/moments.h), as solve_random_walk does: M is linear in E and in R, so with an
// emission or response weights far from 1 every method measures the problem with E / s and the response R / r
// (s = moment_scale(max E), r = moment_scale(max R): powers of two, exact), and M and its standard error are
// multiplied back by s r, the variances by (s r)^2; then refuse_overflow.
Measurement measure_by_method(const RadiosityProblem& problem, const PatchSet* patches, const Visibility* visibility,
                              const Response& response, const MeasureOptions& o) {
  const double s = moment_scale(problem.max_emission());
  const double r = moment_scale(response.R.size() > 0 ? response.R.maxCoeff() : 0.0);
  Measurement m;
  if (s == 1 && r == 1) {
    m = measure_unscaled(problem, patches, visibility, response, o);
  } else {
    std::optional<RadiosityProblem> scaled;
    if (s != 1) {
      scaled.emplace(problem);
      scaled->E /= s;
    }
    Response weights = response;
    weights.R /= r;
    m = measure_unscaled(scaled ? *scaled : problem, patches, visibility, weights, o);
    // M s r, not M (s r): s r may overflow where the product does not.
    m.estimate.M = m.estimate.M * s * r;
    m.estimate.se = m.estimate.se * s * r;
    m.estimate.var = m.estimate.var * s * s * r * r;
    m.estimate.var_theory = m.estimate.var_theory * s * s * r * r;
  }
  refuse_overflow(m.estimate, o.method, response);
  return m;
}

}  // namespace radwalk
