// Stability refusals: each cause gives its status and a message that names the cause and the remedy.
#include <catch2/catch.hpp>

#include "scenes.h"
#include "solve/convergence.h"
#include "solve/solve_radiosity.h"

using namespace radwalk;
using namespace radwalk::test;
using Catch::Matchers::Contains;

namespace {

const std::vector<std::string> kIterative = {"jacobi", "gauss-seidel", "southwell"};

Solution run(const std::string& solver, const RadiosityProblem& p, long max_iterations = 10000) {
  SolveOptions o;
  o.solver = solver;
  o.max_iterations = max_iterations;
  return solve_radiosity(p, o);
}

void check_finite_or_empty(const Solution& s) {
  CHECK(s.B.allFinite());  // never NaN, whatever the status
}

}  // namespace

TEST_CASE("rho = 1 in a closed scene with emission: direct refuses, iterations diverge", "[solve][stability]") {
  const RadiosityProblem p = lit_cube(Rgb::Ones(), Rgb(1, 1, 1));
  for (const std::string solver : {"direct", "auto"}) {
    const Solution s = run(solver, p);
    INFO(solver << ": " << s.message);
    CHECK(s.status == SolveStatus::refused);
    CHECK_THAT(s.message, Contains("refused") && Contains("spectral radius") && Contains("reflectance"));
    CHECK(s.B.size() == 0);
  }
  for (const auto& solver : kIterative) {
    const Solution s = run(solver, p);
    INFO(solver << ": " << s.message);
    CHECK(s.status == SolveStatus::diverged);
    CHECK_THAT(s.message, Contains("cannot converge") && Contains("spectral radius") && Contains("reflectances"));
    CHECK(s.iterations == 0);  // refused before iterating
    CHECK(s.info.at("spectral_radius_estimate") == Approx(1).epsilon(kRadiusOneTolerance));
    check_finite_or_empty(s);
  }
}

TEST_CASE("rows of F summing above 1: no physical solution", "[solve][stability]") {
  const double scale = 1.25, rho = 0.9;  // radius rho * scale = 1.125
  const RadiosityProblem p = cube(Rgb::Constant(rho), PatchRgb::Constant(6, 3, 1.0), scale);
  const Solution direct = run("direct", p);
  INFO(direct.message);
  CHECK(direct.status == SolveStatus::refused);
  CHECK_THAT(direct.message, Contains("not an M-matrix") && Contains("form-factor rows must sum to <= 1"));
  for (const auto& solver : kIterative) {
    const Solution s = run(solver, p);
    INFO(solver << ": " << s.message);
    CHECK(s.status == SolveStatus::diverged);
    CHECK_THAT(s.message, Contains("max row sum of F = 1.25") && Contains("rows must sum to <= 1"));
    CHECK(s.info.at("spectral_radius_estimate") == Approx(rho * scale).epsilon(1e-6));
    check_finite_or_empty(s);
  }
}

TEST_CASE("too slow for the budget: max_iterations with the iterations needed", "[solve][stability]") {
  // Furnace rho = 0.99: Jacobi needs log(1e-10) / log(0.99) = 2291 sweeps, Gauss-Seidel at best half of that.
  const RadiosityProblem p = furnace(0.99, 1.0);
  for (const auto& solver : kIterative) {
    const Solution s = run(solver, p, 100);
    INFO(solver << ": " << s.message);
    CHECK(s.status == SolveStatus::max_iterations);
    CHECK_THAT(s.message, Contains("would not reach tol") && Contains("max-iterations 100") &&
                              Contains("Raise --max-iterations") && Contains("direct solver"));
    CHECK(s.info.at("iterations_needed") >= (solver == "jacobi" ? 2291 : 1146));
    check_finite_or_empty(s);
  }
  CHECK(run("direct", p).status == SolveStatus::converged);
  // Within budget the same problem converges.
  CHECK(run("gauss-seidel", p, 3000).status == SolveStatus::converged);
}

TEST_CASE("the residual watch: growth, stagnation, a rate too slow, convergence", "[solve][stability]") {
  SolveOptions o;
  o.tol = 1e-10;
  o.max_iterations = 1000;
  std::string why;
  std::vector<double> growing;
  for (int k = 0; k < 40; ++k) growing.push_back(std::pow(1.3, k));  // growing over a full window at k = 20
  std::vector<double> h;
  Verdict verdict = Verdict::keep_going;
  for (double r : growing) {
    h.push_back(r);
    verdict = judge_progress(h, 1, o, "jacobi", &why);
    if (verdict != Verdict::keep_going) break;
  }
  CHECK(verdict == Verdict::diverged);
  CHECK(h.size() == 2 * kRateWindow + 1);
  CHECK_THAT(why, Contains("grew"));

  std::vector<double> flat(25, 1e-8);
  CHECK(judge_progress(flat, 1, o, "jacobi", &why) == Verdict::stagnated);
  CHECK_THAT(why, Contains("rounding level"));

  std::vector<double> slow;  // 0.99 per sweep needs about 2291 sweeps > 1000
  for (int k = 0; k < 25; ++k) slow.push_back(std::pow(0.99, k));
  CHECK(judge_progress(slow, 1, o, "jacobi", &why) == Verdict::too_slow);
  CHECK_THAT(why, Contains("observed rate 0.99"));
  o.max_iterations = 3000;
  CHECK(judge_progress(slow, 1, o, "jacobi", &why) == Verdict::keep_going);

  CHECK(judge_progress({1.0, 1e-11}, 1, o, "jacobi", &why) == Verdict::converged);
  CHECK(judge_progress({1.0, std::nan("")}, 1, o, "jacobi", &why) == Verdict::diverged);
  CHECK(judge_progress({1e-3, 1.1}, 1, o, "jacobi", &why) == Verdict::diverged);  // 1e3 above its minimum
}
