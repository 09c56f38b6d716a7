// The constant control variate of the gathering walks (walk/control_variate.h): exact in a uniform closed scene,
// unbiased elsewhere, its exact variance right, and refused where it does not apply.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/error.h"
#include "solve/direct_solver.h"
#include "support/statistics.h"
#include "visibility/brute_force_visibility.h"
#include "walk/control_variate.h"
#include "walk/random_walk_solver.h"
#include "walk/walk_variance.h"
#include "walk_test_scenes.h"

using namespace radwalk;

TEST_CASE("control variate: in a uniform closed cube B is constant, so E' = 0 and every walk is exact",
          "[walk][control_variate]") {
  // rho = 0.5 and E = 1 on every face of the closed cube (rows of F sum to 1): B = E / (1 - rho) = 2 = c.
  const RadiosityProblem p = test::cube_problem(PatchRgb::Constant(6, 3, 0.5), PatchRgb::Constant(6, 3, 1.0));
  const ControlVariate cv = constant_control_variate(p);
  for (int c = 0; c < 3; ++c) CHECK(cv.c(c) == Approx(2.0).epsilon(1e-6));  // float F: row sums 1 to rounding
  CHECK(cv.E_shifted.abs().maxCoeff() < 1e-6);
  WalkOptions o;
  o.method = WalkMethod::gather_collision;
  o.walks_per_patch = 200;
  o.control_variate = true;
  const Solution s = solve_random_walk(p, nullptr, nullptr, o);
  CHECK((s.B - 2.0).abs().maxCoeff() < 1e-5);
  CHECK(s.var.maxCoeff() < 1e-10);  // against a per-walk variance of E^2 rho / (1 - rho)^2 = 2 without it
  o.control_variate = false;
  CHECK(solve_random_walk(p, nullptr, nullptr, o).var.minCoeff() > 0.1);
}

TEST_CASE("control variate: every gathering method unbiased, its exact variance matches the sample variance",
          "[walk][control_variate][statistical]") {
  const RadiosityProblem p = test::mixed_cube();
  const PatchRgb B = dense_radiosity(p);
  // 3 methods x 6 patches x 3 channels z-tests of B, family-wise alpha = 1e-3.
  const double z = z_critical(sidak(1e-3, 3 * 6 * 3));
  for (const WalkMethod m : {WalkMethod::gather_collision, WalkMethod::gather_absorption,
                             WalkMethod::gather_expected_value}) {
    WalkOptions o;
    o.method = m;
    o.walks_per_patch = 40000;
    o.seed = 5;
    o.control_variate = true;
    o.theory = true;
    const Solution s = solve_random_walk(p, nullptr, nullptr, o);
    INFO(method_name(m));
    REQUIRE(s.status == SolveStatus::converged);
    for (Eigen::Index i = 0; i < 6; ++i)
      for (int c = 0; c < 3; ++c) {
        INFO("patch " << i << " channel " << c << ": " << s.B(i, c) << " +- " << s.B_se(i, c) << " vs " << B(i, c));
        CHECK(std::abs(s.B(i, c) - B(i, c)) <= z * s.B_se(i, c));
      }
    // The exact per-walk variance of the shifted walks against their sample variance: the mean over patches and
    // channels of var / var_theory is 1 within a few per cent at 40,000 walks (each ratio's relative error is
    // about sqrt((kurtosis - 1) / n), under 2 % for these bounded scores; 5 % allows 2.5 of those).
    const double ratio = (s.var / s.var_theory).mean();
    CHECK(ratio == Approx(1.0).epsilon(0.05));
    // Not asserted: that the variance is lower. It is not a property of the method: on this cube the summed
    // exact variance falls for collision and expected value but rises for absorption (100.9 against 92.6).
  }
}

TEST_CASE("control variate: refused for shooting and without F", "[walk][control_variate]") {
  const RadiosityProblem p = test::mixed_cube();
  WalkOptions o;
  o.method = WalkMethod::shoot_collision;
  o.control_variate = true;
  CHECK_THROWS_AS(solve_random_walk(p, nullptr, nullptr, o), InputError);
  o.method = WalkMethod::gather_collision;
  o.kernel = WalkKernel::ray;
  RadiosityProblem no_f = p;
  no_f.F = SparseF();
  const PatchSet patches = test::cube_patches(p);
  const BruteForceVisibility vis(patches);
  CHECK_THROWS_AS(solve_random_walk(no_f, &patches, &vis, o), InputError);
}
