// Failures the random walks must detect and report, beside what tests/solve/test_stability.cpp checks for the
// deterministic solvers on the same inputs: rho = 1 in a closed scene (walks would never end), rho = 1 in one
// channel only (walks end, but that channel's series diverges), and form-factor rows summing above 1.
#include <catch2/catch.hpp>

#include "core/error.h"
#include "failure_scenes.h"
#include "solve/solve_radiosity.h"
#include "walk/random_walk_solver.h"
#include "walk/walk_variance.h"

using namespace radwalk;
using namespace radwalk::test;
using Catch::Matchers::Contains;

namespace {

std::string input_error(const RadiosityProblem& p, const WalkOptions& o) {
  try {
    solve_random_walk(p, nullptr, nullptr, o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

Solution run(const std::string& solver, const RadiosityProblem& p) {
  SolveOptions o;
  o.solver = solver;
  return solve_radiosity(p, o);
}

}  // namespace

TEST_CASE("rho = 1 in a closed scene: every walk method is refused, a walk would never end", "[failure][walk]") {
  const RadiosityProblem p = box(Rgb::Ones());
  for (const WalkMethod method : all_walk_methods()) {
    for (const SurvivalRule survival : {SurvivalRule::analog, SurvivalRule::max}) {
      WalkOptions o;
      o.method = method;
      o.survival.rule = survival;
      o.walks_per_patch = o.particles = 10;
      const std::string what = input_error(p, o);
      INFO(method_name(method) << ", survival " << survival_name(survival) << ": '" << what << "'");
      CHECK_THAT(what, Contains("survival probability p = 1") && Contains("might never end"));
    }
  }
}

TEST_CASE("rho = 1 in one channel only: every solver, walks included, refuses and names the channel",
          "[failure][walk]") {
  // Red reflects everything in a closed box: no finite red radiosity. Analog survival (mean rho = 2/3) would end
  // every walk, but the red weights grow without bound: the walks refuse the system (status diverged) before
  // walking, naming the channel, as the deterministic solvers do.
  const RadiosityProblem p = box(Rgb(1.0, 0.5, 0.5));
  const Solution direct = run("direct", p);
  INFO(direct.message);
  CHECK(direct.status == SolveStatus::refused);
  CHECK_THAT(direct.message, Contains("channel 0"));
  for (const std::string solver : {"jacobi", "gauss-seidel", "southwell"}) {
    const Solution s = run(solver, p);
    INFO(solver << ": " << s.message);
    CHECK(s.status == SolveStatus::diverged);
    CHECK_THAT(s.message, Contains("channel 0"));
  }
  for (const WalkMethod method : all_walk_methods()) {
    WalkOptions o;
    o.method = method;
    o.walks_per_patch = o.particles = 50;
    const Solution s = solve_random_walk(p, nullptr, nullptr, o);
    INFO(method_name(method) << ": " << s.message);
    CHECK(s.status == SolveStatus::diverged);
    CHECK(s.B.size() == 0);  // no estimate is returned for a system with no solution
    CHECK_THAT(s.message, Contains("channel 0"));
    CHECK_THAT(s.message, Contains("no finite solution"));
  }
}

TEST_CASE("form-factor rows above 1: the walks refuse a system with no solution", "[failure][walk]") {
  // Rows scaled to 1.25 with rho 0.9: radius(diag(rho) F) = 1.125 (no solution; the deterministic solvers'
  // refusals are in test_stability.cpp). The walks refuse it too, naming the row sum.
  const RadiosityProblem p = box(Rgb::Constant(0.9), {0, 1, 2, 3, 4, 5}, 1.25);
  for (const WalkMethod method : all_walk_methods()) {
    WalkOptions o;
    o.method = method;
    o.walks_per_patch = o.particles = 50;
    const Solution s = solve_random_walk(p, nullptr, nullptr, o);
    INFO(method_name(method) << ": " << s.message);
    CHECK(s.status == SolveStatus::diverged);
    CHECK(s.info.at("spectral_radius") == Approx(0.9 * 1.25).epsilon(1e-4));
    CHECK_THAT(s.message, Contains("max row sum of F 1.25"));
  }
  // Rows above 1 with a radius below 1 (rho 0.5: 0.625) have a finite, non-physical solution the walks estimate
  // with finite variance: nothing in the library flags it (the CLI refuses such a Matrix Market file on reading).
  const RadiosityProblem q = box(Rgb::Constant(0.5), {0, 1, 2, 3, 4, 5}, 1.25);
  WalkOptions o;
  o.method = WalkMethod::gather_absorption;
  o.walks_per_patch = 50;
  CHECK(solve_random_walk(q, nullptr, nullptr, o).info.at("variance_radius") < 1);
}
