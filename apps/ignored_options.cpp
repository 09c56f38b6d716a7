#include "apps/ignored_options.h"

#include <algorithm>

#include "walk/measure_by_method.h"

namespace radwalk::app {
namespace {

// Options that apply only when `applies` holds; `used_only` completes "... does not apply here (used only ...)".
template <class Command>
struct Rule {
  std::vector<std::string> options;
  bool (*applies)(const Command&);
  const char* used_only;
};

bool random_walk(const SolveCommand& c) { return c.solver == "random-walk"; }
bool hierarchical(const SolveCommand& c) { return c.hierarchical; }
// --target-error on the hierarchical route (`hierarchical` is set by then: apps/options.h, target_route) with
// --hierarchical-transport form-factors: the leaves solved by the traced F.
bool leaf_form_factors(const SolveCommand& c) {
  return c.hierarchical && c.target_error > 0 && c.hierarchical_transport == "form-factors";
}

// Walk options by their command-line names.
const std::vector<Rule<SolveCommand>> kSolveRules = {
    {{"--walk", "--estimator", "--kernel", "--walks-per-patch", "--particles", "--patches", "--survival",
      "--survival-constant", "--theory"},
     random_walk, "with --solver random-walk"},
    {{"--tol", "--max-iterations"},
     [](const SolveCommand& c) { return c.solver != "direct" && !random_walk(c) && !hierarchical(c); },
     "by the iterative solvers: --solver jacobi, gauss-seidel, southwell, or auto above 2000 patches"},
    {{"--hierarchical-tol", "--hierarchical-levels", "--hierarchical-min-area", "--hierarchical-points",
      "--hierarchical-rays", "--hierarchical-replicates", "--hierarchical-refine", "--hierarchical-clusters"},
     hierarchical, "with --hierarchical, or --target-error on its default route, the hierarchical one"},
    {{"--hierarchical-cluster-ratio"},
     [](const SolveCommand& c) { return hierarchical(c) && c.hierarchical_clusters == "on"; },
     "with --hierarchical --hierarchical-clusters on"},
    {{"--hierarchical-tol"}, [](const SolveCommand& c) { return c.hierarchical_refine == "oracle"; },
     "with --hierarchical-refine oracle (the estimate's refinement has no a-priori oracle)"},
    {{"--hierarchical-target", "--hierarchical-max-leaves", "--hierarchical-steps"},
     [](const SolveCommand& c) { return hierarchical(c) && c.hierarchical_refine == "estimate"; },
     "with --hierarchical --hierarchical-refine estimate"},
    {{"--survival-constant"}, [](const SolveCommand& c) { return c.walk.survival.rule == SurvivalRule::constant; },
     "with --survival constant"},
    {{"--patches"}, [](const SolveCommand& c) { return is_gathering(c.walk.method); },
     "when gathering (--walk gather); shooting estimates every patch"},
    {{"--rays", "--rays-per-area", "--min-rays", "--form-factors", "--reciprocity", "--enforce-closure", "--sobol-rays", "--emitter-columns",
      "--analytic", "--analytic-cutoff", "--analytic-cutoff-rays", "--visibility-samples", "--normalise-rows"},
     [](const SolveCommand& c) { return !(random_walk(c) && c.walk.kernel == WalkKernel::ray); },
     "for form factors, which --kernel ray does not use"},
    {{"--rays-per-area", "--min-rays", "--form-factors", "--reciprocity", "--sobol-rays", "--emitter-columns",
      "--analytic", "--analytic-cutoff", "--analytic-cutoff-rays", "--visibility-samples", "--normalise-rows"},
     [](const SolveCommand& c) { return !hierarchical(c) || leaf_form_factors(c); },
     "for form factors, which --hierarchical uses only with --target-error and --hierarchical-transport "
     "form-factors (the default)"},
    {{"--hierarchical-transport", "--hierarchical-split"},
     [](const SolveCommand& c) { return hierarchical(c) && c.target_error > 0; },
     "with --target-error on its default route, the hierarchical one"},
    {{"--hierarchical-points", "--hierarchical-replicates"},
     [](const SolveCommand& c) { return !leaf_form_factors(c); },
     "by the hierarchical stochastic Jacobi (--hierarchical-transport rays): with form-factors the direct light is "
     "the exact emitter columns and the standard errors come from F"},
    {{"--rays"}, [](const SolveCommand& c) { return !hierarchical(c) || c.target_error > 0; },
     "for form factors, which --hierarchical does not use"},  // with --target-error: the first step's rays per leaf
    {{"--hierarchical-tol", "--hierarchical-rays", "--hierarchical-refine", "--hierarchical-target",
      "--hierarchical-max-leaves", "--hierarchical-steps"},
     [](const SolveCommand& c) { return !(c.target_error > 0); },
     "without --target-error (with --hierarchical it refines by the estimate and chooses the rays itself: --rays "
     "sets the first step's rays per leaf, --max-patches the budget of leaves)"},
    {{"--hierarchical-clusters", "--hierarchical-cluster-ratio"},
     [](const SolveCommand& c) { return !(c.target_error > 0); },
     "without --target-error, whose steps solve the leaves unclustered"},
    {{"--min-rays"}, [](const SolveCommand& c) { return c.ff.rays_per_area > 0; }, "with --rays-per-area"},
    {{"--refine-steps", "--refine-floor", "--refine-noise"}, [](const SolveCommand& c) { return c.refine > 0; },
     "with --refine"},
    {{"--max-patches"}, [](const SolveCommand& c) { return c.refine > 0 || c.target_error > 0; },
     "with --refine or --target-error"},
    {{"--solver", "--form-factors", "--analytic", "--rays-per-area", "--min-rays", "--progressive", "--enforce-closure"},
     [](const SolveCommand& c) { return !(c.target_error > 0); },
     "without --target-error (it chooses the solver and the rays of the traced form-factor route itself)"},
    {{"--enforce-closure"}, [](const SolveCommand& c) { return !(c.refine > 0); },
     "without --refine (adaptive patching traces its own form factors at every step)"},
    {{"--discretisation-directions"}, [](const SolveCommand& c) { return !(c.refine > 0); },
     "without --refine (adaptive patching does not estimate B_disc yet)"},
};

const std::vector<Rule<ExchangeCommand>> kExchangeRules = {
    {{"--walk", "--estimator", "--walks-per-patch", "--particles", "--survival", "--survival-constant"},
     [](const ExchangeCommand& c) { return c.solver == "random-walk"; }, "with --solver random-walk"},
    {{"--survival-constant"}, [](const ExchangeCommand& c) { return c.walk.survival.rule == SurvivalRule::constant; },
     "with --survival constant"},
    {{"--tol", "--max-iterations"},
     [](const ExchangeCommand& c) { return c.solver != "direct" && c.solver != "random-walk"; },
     "by the iterative solvers: --solver jacobi, gauss-seidel, southwell, or auto above 2000 patches"},
    {{"--min-rays"}, [](const ExchangeCommand& c) { return c.ff.rays_per_area > 0; }, "with --rays-per-area"},
};

const std::vector<Rule<FormFactorsCommand>> kFormFactorsRules = {
    {{"--min-rays"}, [](const FormFactorsCommand& c) { return c.ff.rays_per_area > 0; }, "with --rays-per-area"},
};

const std::vector<Rule<CompareCommand>> kCompareRules = {
    {{"--min-rays"}, [](const CompareCommand& c) { return c.ff.rays_per_area > 0; }, "with --rays-per-area"},
};

bool walk_method(const MeasureCommand& c) {
  return !is_deterministic_measure(c.method) && !is_importance_measure(c.method);
}

const std::vector<Rule<MeasureCommand>> kMeasureRules = {
    {{"--kernel", "--survival", "--survival-constant"}, walk_method,
     "by the walk methods (--method gather-*, shoot-*); direct, adjoint-direct and the importance walks use the "
     "matrix of form factors"},
    {{"--walks", "--theory"}, [](const MeasureCommand& c) { return !is_deterministic_measure(c.method); },
     "by the Monte Carlo methods, not by --method direct or adjoint-direct"},
    {{"--importance-sweeps", "--defensive"}, [](const MeasureCommand& c) { return is_importance_measure(c.method); },
     "with --method importance-gather or importance-shoot"},
    {{"--survival-constant"}, [](const MeasureCommand& c) { return c.walk.survival.rule == SurvivalRule::constant; },
     "with --survival constant"},
    {{"--rays", "--rays-per-area", "--min-rays", "--form-factors", "--reciprocity", "--enforce-closure", "--sobol-rays", "--emitter-columns",
      "--discretisation-directions"},
     [](const MeasureCommand& c) { return !(walk_method(c) && c.walk.kernel == WalkKernel::ray); },
     "for form factors and the discretisation estimate from B, which --kernel ray does not use"},
    {{"--min-rays"}, [](const MeasureCommand& c) { return c.ff.rays_per_area > 0; }, "with --rays-per-area"},
    {{"--camera", "--width", "--height"}, [](const MeasureCommand& c) { return c.response == "camera"; },
     "with --response camera"},
};

const std::vector<Rule<PathtraceCommand>> kPathtraceRules = {
    {{"--width", "--height", "--camera"}, [](const PathtraceCommand& c) { return !c.image.empty(); },
     "with --image"},
};

template <class Command>
std::vector<std::string> apply(const std::vector<Rule<Command>>& rules, const Command& command,
                               const OptionGiven& given) {
  std::vector<std::string> reported, warnings;
  for (const Rule<Command>& rule : rules) {
    if (rule.applies(command)) continue;
    std::vector<std::string> ignored;
    for (const std::string& o : rule.options)
      if (given(o) && std::find(reported.begin(), reported.end(), o) == reported.end()) ignored.push_back(o);
    if (ignored.empty()) continue;
    std::string names;
    for (std::size_t k = 0; k < ignored.size(); ++k)
      names += (k == 0 ? "" : k + 1 == ignored.size() ? " and " : ", ") + ignored[k];
    warnings.push_back(names + (ignored.size() == 1 ? " does" : " do") + " not apply here (used only " +
                       rule.used_only + "): remove " + (ignored.size() == 1 ? "it" : "them"));
    reported.insert(reported.end(), ignored.begin(), ignored.end());
  }
  return warnings;
}

}  // namespace

std::vector<std::string> ignored_options(const SolveCommand& command, const OptionGiven& given) {
  return apply(kSolveRules, command, given);
}
std::vector<std::string> ignored_options(const ExchangeCommand& command, const OptionGiven& given) {
  return apply(kExchangeRules, command, given);
}
std::vector<std::string> ignored_options(const FormFactorsCommand& command, const OptionGiven& given) {
  return apply(kFormFactorsRules, command, given);
}
std::vector<std::string> ignored_options(const CompareCommand& command, const OptionGiven& given) {
  return apply(kCompareRules, command, given);
}
std::vector<std::string> ignored_options(const MeasureCommand& command, const OptionGiven& given) {
  return apply(kMeasureRules, command, given);
}
std::vector<std::string> ignored_options(const PathtraceCommand& command, const OptionGiven& given) {
  return apply(kPathtraceRules, command, given);
}

}  // namespace radwalk::app
