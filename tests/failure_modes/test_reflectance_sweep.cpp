// Sweep-level failure modes: how iterations, conditioning, walk length and variance degrade as rho -> 1 in a
// closed scene, and that an opening keeps them bounded. The single-point refusals (rho = 1, rows above 1, one
// budget too small) are in tests/solve/test_stability.cpp and tests/walk/test_variance.cpp; these tests check the
// laws across the sweep that the failure_modes experiment charts.
#include <catch2/catch.hpp>
#include <cmath>

#include "failure_scenes.h"
#include "solve/solve_radiosity.h"
#include "walk/random_walk_solver.h"
#include "walk/walk_variance.h"

using namespace radwalk;
using namespace radwalk::test;
using Catch::Matchers::Contains;

namespace {

const double kSweep[] = {0.1, 0.5, 0.9, 0.99, 0.999};

Solution run(const std::string& solver, const RadiosityProblem& p, double tol, long max_iterations) {
  SolveOptions o;
  o.solver = solver;
  o.tol = tol;
  o.max_iterations = max_iterations;
  return solve_radiosity(p, o);
}

}  // namespace

TEST_CASE("reflectance sweep: Jacobi needs ceil(log tol / log rho) sweeps, Gauss-Seidel no more, kappa (1+rho)/(1-rho)",
          "[failure][sweep]") {
  const double tol = 1e-8;
  long previous = 0;
  for (double rho : kSweep) {
    const RadiosityProblem p = complete(5, rho);
    const double law = std::log(tol) / std::log(rho);
    const Solution jacobi = run("jacobi", p, tol, 100000);
    INFO("rho " << rho << ": " << jacobi.message);
    REQUIRE(jacobi.status == SolveStatus::converged);
    // Residual of B^(k-1) is rho^k exactly: sweep k = ceil(law) is the first to meet tol (+-1 for rounding).
    CHECK(std::abs(double(jacobi.iterations) - std::ceil(law)) <= 1);
    // The prediction made before iterating (rate_factor 1 for Jacobi) is the same law, rounded up.
    CHECK(std::abs(jacobi.info.at("iterations_needed") - std::ceil(law)) <= 1);
    CHECK(jacobi.iterations > previous);  // grows with rho
    previous = jacobi.iterations;

    const Solution gs = run("gauss-seidel", p, tol, 100000);
    INFO(gs.message);
    CHECK(gs.status == SolveStatus::converged);
    CHECK(gs.iterations <= jacobi.iterations);  // Stein-Rosenberg

    const Solution direct = run("direct", p, tol, 1);
    INFO(direct.message);
    REQUIRE(direct.status == SolveStatus::converged);
    CHECK(direct.info.at("condition_estimate") == Approx((1 + rho) / (1 - rho)).epsilon(1e-6));
    CHECK(direct.B(0, 0) == Approx(1 / (1 - rho)).epsilon(1e-9 * (1 + rho) / (1 - rho)));
  }
}

TEST_CASE("reflectance sweep: the budget refusal predicts the sweeps the converged run then takes", "[failure][sweep]") {
  // With max-iterations below the law the run is refused (status max_iterations, nothing iterated) and the message
  // names the count; given that count it converges within it.
  const double tol = 1e-8;
  for (double rho : {0.9, 0.99, 0.999}) {
    const RadiosityProblem p = complete(5, rho);
    const long law = long(std::ceil(std::log(tol) / std::log(rho)));
    const Solution refused = run("jacobi", p, tol, law / 2);
    INFO("rho " << rho << ": " << refused.message);
    CHECK(refused.status == SolveStatus::max_iterations);
    CHECK(refused.iterations == 0);
    CHECK_THAT(refused.message, Contains("needs about") && Contains("Raise --max-iterations"));
    const double needed = refused.info.at("iterations_needed");
    const Solution ok = run("jacobi", p, tol, long(std::ceil(needed)) + 1);
    INFO(ok.message);
    CHECK(ok.status == SolveStatus::converged);
    CHECK(ok.iterations <= long(std::ceil(needed)) + 1);
  }
}

TEST_CASE("rho -> 1 in float: direct refuses once kappa exceeds 2^24, iterations by budget or radius", "[failure][sweep]") {
  // rho = 1 - 1e-5: kappa 2e5, solvable directly; Jacobi would need log(1e-10) / 1e-5 = 2.3e6 sweeps.
  const RadiosityProblem near = complete(5, 1 - 1e-5);
  const Solution d = run("direct", near, 1e-10, 1);
  INFO(d.message);
  CHECK(d.status == SolveStatus::converged);
  CHECK(d.info.at("condition_estimate") == Approx(2e5).epsilon(1e-3));
  const Solution j = run("jacobi", near, 1e-10, 10000);
  INFO(j.message);
  CHECK(j.status == SolveStatus::max_iterations);
  CHECK(j.info.at("iterations_needed") == Approx(std::log(1e-10) / std::log(1 - 1e-5)).epsilon(1e-3));

  // rho = 1 - 1e-8: kappa 2e8 > 1.7e7 = 1/2^-24: the float F determines no digit of B.
  const RadiosityProblem nearer = complete(5, 1 - 1e-8);
  const Solution r = run("direct", nearer, 1e-10, 1);
  INFO(r.message);
  CHECK(r.status == SolveStatus::refused);
  CHECK_THAT(r.message, Contains("numerically singular") && Contains("determine no digit"));
  CHECK(r.B.size() == 0);
  // The iterations treat a radius within 1e-6 of 1 as 1.
  for (const std::string solver : {"jacobi", "gauss-seidel", "southwell"}) {
    const Solution s = run(solver, nearer, 1e-10, 10000);
    INFO(solver << ": " << s.message);
    CHECK(s.status == SolveStatus::diverged);
    CHECK_THAT(s.message, Contains("cannot converge"));
    CHECK(s.B.allFinite());
  }
}

TEST_CASE("open against closed box at rho = 0.999: the opening bounds the iterations", "[failure][sweep]") {
  const Rgb rho = Rgb::Constant(0.999);
  const RadiosityProblem closed = box(rho);
  const RadiosityProblem open = box(rho, {0, 1, 2, 3, 5});  // wall z = 0 removed
  const Solution c = run("jacobi", closed, 1e-10, 10000);
  INFO(c.message);
  CHECK(c.status == SolveStatus::max_iterations);  // needs about 23000 sweeps
  CHECK(c.info.at("iterations_needed") > 10000);
  const Solution o = run("jacobi", open, 1e-10, 10000);
  INFO(o.message);
  CHECK(o.status == SolveStatus::converged);
  const double radius = o.info.at("spectral_radius_estimate");
  CHECK(radius < 0.999 * 0.85);  // the rows of an open box sum to 0.8 (4 of 5 neighbours kept)
  CHECK(std::abs(o.iterations - std::log(1e-10) / std::log(radius)) <= 0.1 * std::log(1e-10) / std::log(radius) + 2);

  // Random walks: in the open box walks escape, so they end even though rho is almost 1.
  WalkOptions w;
  w.method = WalkMethod::gather_collision;
  w.walks_per_patch = 2000;
  const Solution wo = solve_random_walk(open, nullptr, nullptr, w);
  CHECK(wo.info.at("escapes") > 0);
  const Solution wc = solve_random_walk(closed, nullptr, nullptr, w);
  CHECK(wc.info.at("escapes") == 0);
  CHECK(double(wc.steps) / double(wc.walks) > 20 * double(wo.steps) / double(wo.walks));
}

TEST_CASE("reflectance sweep: analog walks take rho / (1 - rho) steps, collision relative variance is rho",
          "[failure][sweep][walk]") {
  // Closed scene, analog survival p = rho: the number of transitions of a gathering walk is geometric with mean
  // rho / (1 - rho) and variance rho / (1 - rho)^2. Five z-tests at alpha = 1e-4 each (Sidak: 5e-4 overall).
  const double z_crit = 3.89;
  for (double rho : kSweep) {
    const RadiosityProblem p = complete(5, rho, 2.0);
    WalkOptions w;
    w.method = WalkMethod::gather_collision;
    w.walks_per_patch = 2000;
    w.seed = 7;
    const Solution s = solve_random_walk(p, nullptr, nullptr, w);
    const double mean = rho / (1 - rho), var = rho / ((1 - rho) * (1 - rho));
    const double walks = double(s.walks);
    const double z = (double(s.steps) / walks - mean) / std::sqrt(var / walks);
    INFO("rho " << rho << ": " << s.steps << " steps over " << s.walks << " walks, z " << z);
    CHECK(std::abs(z) < z_crit);
    CHECK(s.info.at("variance_radius") == Approx(rho).epsilon(1e-5));  // K = rho F: finite for every rho < 1
    // Exact variance (walk_variance.h): collision var / B^2 = rho (bounded: the cost grows, not the relative
    // variance); absorption 0 (rounding only).
    const PatchRgb B = dense_radiosity(p);
    const PatchRgb vc = theoretical_variance(p, w, B);
    CHECK(vc(0, 0) / (B(0, 0) * B(0, 0)) == Approx(rho).epsilon(1e-4));
    WalkOptions a = w;
    a.method = WalkMethod::gather_absorption;
    const PatchRgb va = theoretical_variance(p, a, B);
    CHECK(std::abs(va(0, 0)) <= 1e-9 * B(0, 0) * B(0, 0));
  }
}

TEST_CASE("constant survival across the sweep: variance finite iff rho^2 / p < 1, reported otherwise",
          "[failure][sweep][walk]") {
  // K = diag(rho^2 n / p) F with rows summing to 1: radius rho^2 / p. p = 0.5 -> the boundary is rho = 0.7071.
  for (double rho : {0.3, 0.5, 0.7, 0.72, 0.9, 0.99}) {
    const RadiosityProblem p = complete(5, rho);
    WalkOptions w;
    w.method = WalkMethod::gather_collision;
    w.survival = {SurvivalRule::constant, 0.5};
    w.walks_per_patch = 200;
    const VarianceCheck check = check_finite_variance(p, w);
    INFO("rho " << rho << ": radius " << check.radius);
    CHECK(check.radius == Approx(rho * rho / 0.5).epsilon(1e-5));
    CHECK(check.finite() == (rho * rho < 0.5));
    const Solution s = solve_random_walk(p, nullptr, nullptr, w);
    INFO(s.message);
    CHECK((s.message.find("variance is infinite") != std::string::npos) == !check.finite());
    CHECK(s.status == SolveStatus::converged);  // the estimate is unbiased; only its error bars are not
  }
}
