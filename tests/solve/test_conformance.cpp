// One conformance check that every solver passes (docs/ARCHITECTURE.md, convention 9): same scenes, same reference
// (dense LU in double, written independently in scenes.h), status reported, input untouched.
#include <catch2/catch.hpp>
#include <functional>

#include "core/error.h"
#include "scenes.h"
#include "solve/residual.h"
#include "solve/solve_radiosity.h"
#include "solve/synthetic_problem.h"

using namespace radwalk;
using namespace radwalk::test;

namespace {

struct NamedProblem {
  std::string name;
  RadiosityProblem p;
};

std::vector<NamedProblem> conformance_scenes() {
  return {
      {"lit cube, rho per channel", lit_cube(Rgb(0.3, 0.5, 0.8), Rgb(10, 20, 30))},
      {"furnace rho 0.5", furnace(0.5, 3.0)},
      {"open parallel plates", plates(Rgb(0.5, 0.6, 0.7), Rgb(0.2, 0.9, 0.4), Rgb(5, 0, 1), Rgb(0, 0, 2))},
      {"sphere with F_ii", sphere(40, 7)},
      {"synthetic MC-like F", make_synthetic_problem(400, 64, 3)},
  };
}

bool same_problem(const RadiosityProblem& a, const RadiosityProblem& b) {
  if (a.F.nonZeros() != b.F.nonZeros() || a.size() != b.size()) return false;
  const SparseF diff = a.F - b.F;
  bool same_F = true;
  for (Eigen::Index i = 0; i < diff.outerSize(); ++i)
    for (SparseF::InnerIterator it(diff, i); it; ++it) same_F = same_F && it.value() == 0;
  return same_F && (a.rho == b.rho).all() && (a.E == b.E).all() && a.area == b.area;
}

using SolverFn = std::function<Solution(const RadiosityProblem&, const SolveOptions&)>;

}  // namespace

TEST_CASE("every solver agrees with dense LU to 1e-9 relative", "[solve][conformance]") {
  const std::vector<std::pair<std::string, SolverFn>> solvers = {
      {"direct", [](const RadiosityProblem& p, const SolveOptions& o) { return solve_direct(p, o); }},
      {"direct (sparse LU)",
       [](const RadiosityProblem& p, const SolveOptions& o) { return solve_direct(p, o, DirectMethod::sparse); }},
      {"jacobi", solve_jacobi},
      {"gauss-seidel", solve_gauss_seidel},
      {"southwell", solve_southwell},
      {"auto", solve_radiosity},
  };
  for (const auto& scene : conformance_scenes()) {
    const PatchRgb reference = dense_reference(scene.p);
    const double kappa = dense_condition(scene.p);
    // ||B - B*|| / ||B*|| <= kappa * relative residual, so this tolerance guarantees 1e-9 (half for the
    // reference's own error, which is kappa * 1e-16).
    SolveOptions options;
    options.tol = 0.5e-9 / kappa;
    options.max_iterations = 2'000'000;
    for (const auto& [name, solve] : solvers) {
      INFO(scene.name << ", " << name << ", kappa " << kappa << ", tol " << options.tol);
      const RadiosityProblem before = scene.p;
      const Solution s = solve(scene.p, options);
      INFO("status " << to_string(s.status) << ": " << s.message);
      CHECK(s.status == SolveStatus::converged);
      CHECK_FALSE(s.message.empty());
      CHECK(s.residual <= options.tol);
      CHECK(s.residual == Approx(relative_residual(scene.p, s.B)).margin(1e-300));
      CHECK(relative_difference(s.B, reference) <= 1e-9);
      CHECK(same_problem(scene.p, before));
      CHECK(s.seconds >= 0);
      CHECK(s.B_se.size() == 0);
      if (name != "direct" && name != "direct (sparse LU)" && name != "auto") {
        CHECK(s.method == name);
        CHECK(s.iterations > 0);
        REQUIRE_FALSE(s.residual_history.empty());
        CHECK(s.residual_history.back() == s.residual);
      }
    }
  }
}

TEST_CASE("the condition estimate of the direct solver is kappa_inf exactly", "[solve][direct]") {
  for (const auto& scene : conformance_scenes()) {
    INFO(scene.name);
    const double kappa = dense_condition(scene.p);
    for (DirectMethod method : {DirectMethod::dense, DirectMethod::sparse}) {
      const Solution s = solve_direct(scene.p, {}, method);
      REQUIRE(s.status == SolveStatus::converged);
      // Computed through one solve instead of the inverse: rounding of order kappa * 1e-16.
      CHECK(s.info.at("condition_estimate") == Approx(kappa).epsilon(kappa * 1e-13));
    }
  }
}

TEST_CASE("solve_radiosity dispatches by name and says what auto chose", "[solve][dispatch]") {
  const RadiosityProblem p = furnace(0.5, 1.0);
  SolveOptions o;
  for (const std::string name : {"direct", "jacobi", "gauss-seidel", "southwell"}) {
    o.solver = name;
    CHECK(solve_radiosity(p, o).method == name);
  }
  o.solver = "auto";
  const Solution s = solve_radiosity(p, o);
  CHECK(s.method == "direct");
  CHECK(s.message.rfind("auto chose direct: 6 patches", 0) == 0);
  o.solver = "conjugate-gradient";
  CHECK_THROWS_AS(solve_radiosity(p, o), InputError);
  o.solver = "auto";
  o.tol = 0;
  CHECK_THROWS_AS(solve_radiosity(p, o), InputError);
}

TEST_CASE("bad problems are InputError, mismatched arrays InternalError, for every solver", "[solve][input]") {
  RadiosityProblem negative = furnace(0.5, 1.0);
  negative.rho(2, 1) = -0.1;
  RadiosityProblem short_E = furnace(0.5, 1.0);
  short_E.E.resize(5, 3);
  RadiosityProblem nan_E = furnace(0.5, 1.0);
  nan_E.E(0, 0) = std::numeric_limits<double>::quiet_NaN();
  for (const std::string name : {"auto", "direct", "jacobi", "gauss-seidel", "southwell"}) {
    SolveOptions o;
    o.solver = name;
    INFO(name);
    CHECK_THROWS_AS(solve_radiosity(negative, o), InputError);
    CHECK_THROWS_AS(solve_radiosity(short_E, o), InternalError);  // arrays of one problem: not user input
    CHECK_THROWS_AS(solve_radiosity(nan_E, o), InputError);
  }
}
