// Measurements M = <R, B>_A: the adjoint identity, every random-walk estimator of M against the direct value,
// exact against empirical per-walk variances, and zero variance of importance-driven walks with exact importance
// (solve/measurement.h, walk/measure_walks.h, walk/importance_walk.h).
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "core/parallel.h"
#include "core/rng.h"
#include "formfactor/form_factors.h"
#include "mesh/read_scene.h"
#include "patch/patching.h"
#include "solve/measurement.h"
#include "solve/synthetic_problem.h"
#include "support/stat_checks.h"
#include "visibility/embree_visibility.h"
#include "walk/importance_walk.h"
#include "walk/measure_walks.h"
#include "walk/walk_variance.h"
#include "walk_test_scenes.h"

using namespace radwalk;

namespace {

// A sensor: the given patches, weight 1.
Response sensor(std::size_t n, const std::vector<int>& patches) {
  Response r{Eigen::VectorXd::Zero(Eigen::Index(n)), "test sensor"};
  for (int i : patches) r.R(i) = 1;
  return r;
}

// The exact M of the problem's own F (dense LU).
Rgb exact_M(const RadiosityProblem& p, const Response& r) { return measure(p.area, r.R, dense_radiosity(p)); }

// <Y, E>_A.
Rgb adjoint_M(const RadiosityProblem& p, const Response& r) {
  const Solution Y = solve_adjoint_direct(p, r);
  REQUIRE(Y.status == SolveStatus::converged);
  return adjoint_measure(p.area, Y.B, p.E);
}

// The synthetic problem (Monte Carlo-like, not reciprocal) with areas varying over [0.5, 2).
RadiosityProblem non_reciprocal(long n) {
  RadiosityProblem p = make_synthetic_problem(n, 200, 3);
  Rng rng = stream(5, StreamDomain::test, 0, 0);
  for (Eigen::Index i = 0; i < p.area.size(); ++i) p.area(i) = 0.5 + 1.5 * rng.uniform();
  return p;
}

RadiosityProblem cornell_box_problem(PatchSet& patches) {
  patches = make_patches(load_scene(std::string(RADWALK_SOURCE_DIR) + "/meshes/cornell_box.obj"), 0.0);
  const EmbreeVisibility visibility(patches);
  FormFactorOptions fo;
  fo.rays_per_patch = 2000;
  fo.seed = 3;
  return make_problem(patches, estimate_form_factors(patches, visibility, fo).F);
}

}  // namespace

TEST_CASE("adjoint identity: <R, B>_A = <Y, E>_A to rounding, with and without reciprocity", "[measure]") {
  // Both sides come from one LU of I - H_c (a substitution and a transposed one): they differ by rounding only,
  // bounded by kappa * N * 2^-53 relative (kappa <= 1 / (1 - max rho * max row sum) = 10 here); 1e-11 allows it.
  SECTION("exact, reciprocal F (the cube)") {
    const RadiosityProblem p = test::mixed_cube();
    for (const auto& patches : {std::vector<int>{0}, std::vector<int>{3}, std::vector<int>{1, 2, 5}}) {
      const Response r = sensor(6, patches);
      const Rgb a = exact_M(p, r), b = adjoint_M(p, r);
      for (int c = 0; c < 3; ++c) CHECK(b(c) == Approx(a(c)).epsilon(1e-11));
    }
  }
  SECTION("Monte Carlo-like F, not reciprocal, unequal areas") {
    const RadiosityProblem p = non_reciprocal(400);
    // F is not reciprocal: A_i F_ij != A_j F_ji somewhere (else the test would not test the transpose).
    double worst = 0;
    for (Eigen::Index i = 0; i < p.F.rows(); ++i)
      for (SparseF::InnerIterator it(p.F, i); it; ++it)
        worst = std::max(worst, std::abs(p.area(i) * it.value() - p.area(it.col()) * p.F.coeff(it.col(), i)));
    REQUIRE(worst > 1e-3);
    Response r = sensor(400, {});
    for (int i = 100; i < 140; ++i) r.R(i) = 0.5 + (i % 3);
    const Rgb a = exact_M(p, r), b = adjoint_M(p, r);
    for (int c = 0; c < 3; ++c) CHECK(b(c) == Approx(a(c)).epsilon(1e-11));
  }
}

TEST_CASE("response checks refuse what cannot be measured", "[measure]") {
  const RadiosityProblem p = test::mixed_cube();
  CHECK_THROWS_AS(solve_adjoint_direct(p, sensor(6, {})), InputError);
  Response r = sensor(6, {1});
  r.R(2) = -1;
  CHECK_THROWS_WITH(solve_adjoint_direct(p, r), Catch::Contains("patch 2") && Catch::Contains(">= 0"));
  CHECK_THROWS_AS(solve_adjoint_direct(p, sensor(5, {1})), InputError);
}

TEST_CASE("every random-walk estimator of M is unbiased on both kernels", "[measure][statistical]") {
  const RadiosityProblem p = test::mixed_cube();
  const PatchSet patches = test::cube_patches(p);
  const EmbreeVisibility visibility(patches);
  const Response r = sensor(6, {3});  // a face that does not emit: M is all reflected light
  const Rgb M = exact_M(p, r);
  // Family: 6 methods x 2 kernels x 3 channels, alpha = 1e-3 family-wise.
  const double z_crit = z_critical(sidak(1e-3, kWalkMethods.size() * 2 * 3));
  test::ZTable table("random-walk estimators of M against the direct M", z_crit);
  for (const auto& row : kWalkMethods)
    for (const WalkKernel kernel : {WalkKernel::matrix, WalkKernel::ray}) {
      WalkOptions o;
      o.method = row.method;
      o.kernel = kernel;
      o.seed = 17;
      const MeasureEstimate e = measure_random_walk(p, &patches, &visibility, o, r, 40000, false);
      for (int c = 0; c < 3; ++c)
        table.add(std::string(row.name) + " " + std::string(kernel_name(kernel)) + " c" + std::to_string(c), e.M(c),
                  e.se(c), M(c));
    }
  table.check();
}

TEST_CASE("exact per-walk variances of the estimators of M match the empirical ones", "[measure][statistical]") {
  // E[sample variance] = variance: the mean of the sample variances of 30 independent runs is tested against the
  // exact variance with the spread of those 30 as its standard error (CLT over the runs).
  const RadiosityProblem p = test::mixed_cube();
  const Response r = sensor(6, {2, 3});
  constexpr int kRuns = 30;
  const double z_crit = z_critical(sidak(1e-3, kWalkMethods.size() * 3));
  test::ZTable table("per-walk variance of M: mean of sample variances against the exact", z_crit);
  for (const auto& row : kWalkMethods) {
    WalkOptions o;
    o.method = row.method;
    Rgb exact = Rgb::Zero();
    std::vector<PowerSums> v(3);
    for (int run = 0; run < kRuns; ++run) {
      o.seed = 100 + std::uint64_t(run);
      const MeasureEstimate e = measure_random_walk(p, nullptr, nullptr, o, r, 4000, run == 0);
      if (run == 0) exact = e.var_theory;
      for (int c = 0; c < 3; ++c) v[std::size_t(c)].add(e.var(c));
    }
    for (int c = 0; c < 3; ++c) {
      REQUIRE(std::isfinite(exact(c)));
      table.add(std::string(row.name) + " c" + std::to_string(c), v[std::size_t(c)].mean(),
                v[std::size_t(c)].standard_error(), exact(c));
    }
  }
  table.check();
}

TEST_CASE("importance-driven walks: zero variance with the exact importance", "[measure]") {
  // With alpha = 0 and g = x every walk scores M exactly (importance_walk.h): the per-walk variance is rounding,
  // far below 1e-20 M^2. The exact variance E[Z^2] - M^2 is a difference of two numbers of size M^2, each from an
  // LU solve accurate to about kappa N 2^-53 relative (kappa the condition number, N <= 40 patches here): it is 0
  // to within 1e-9 M^2 for kappa up to about 1e5.
  auto check_zero = [](const RadiosityProblem& p, const Response& r) {
    const Rgb M = exact_M(p, r);
    const PatchRgb B = dense_radiosity(p);
    const Solution Y = solve_adjoint_direct(p, r);
    REQUIRE(Y.status == SolveStatus::converged);
    const MeasureEstimate g = measure_importance(p, r, ImportanceDirection::from_sensor, B, 0.0, 2000, 5, true);
    const MeasureEstimate s = measure_importance(p, r, ImportanceDirection::from_sources, Y.B, 0.0, 2000, 5, true);
    for (int c = 0; c < 3; ++c) {
      if (!(M(c) > 0)) continue;
      CHECK(g.var(c) < 1e-20 * M(c) * M(c));
      CHECK(s.var(c) < 1e-20 * M(c) * M(c));
      CHECK(g.M(c) == Approx(M(c)).epsilon(1e-12));
      CHECK(s.M(c) == Approx(M(c)).epsilon(1e-12));
      CHECK(g.var_theory(c) < 1e-9 * M(c) * M(c));
      CHECK(s.var_theory(c) < 1e-9 * M(c) * M(c));
    }
  };
  SECTION("the cube, exact F") { check_zero(test::mixed_cube(), sensor(6, {3})); }
  SECTION("the Cornell box, its Monte Carlo F") {
    PatchSet patches;
    const RadiosityProblem p = cornell_box_problem(patches);
    check_zero(p, sensor(p.size(), {0}));
  }
}

TEST_CASE("importance-driven walks with a noisy importance stay unbiased and their variance falls as it improves",
          "[measure][statistical]") {
  const RadiosityProblem p = test::mixed_cube();
  const Response r = sensor(6, {3});
  const Rgb M = exact_M(p, r);
  const PatchRgb B = dense_radiosity(p);
  const Solution Y = solve_adjoint_direct(p, r);
  // Importance B (1 + eps u), u uniform in [-1, 1) per entry, for eps = 0.5, 0.1, 0.01; defensive alpha = 0.1.
  const std::vector<double> eps = {0.5, 0.1, 0.01};
  const double z_crit = z_critical(sidak(1e-3, eps.size() * 2 * 3 * 2));
  test::ZTable means("importance walks with noisy importance: M", z_crit);
  test::ZTable vars("importance walks with noisy importance: per-walk variance against the exact", z_crit);
  for (const auto dir : {ImportanceDirection::from_sensor, ImportanceDirection::from_sources}) {
    const PatchRgb& exact = dir == ImportanceDirection::from_sensor ? B : Y.B;
    Rgb previous = Rgb::Constant(std::numeric_limits<double>::infinity());
    for (double e : eps) {
      Rng rng = stream(9, StreamDomain::test, 1, 0);
      PatchRgb g = exact;
      for (Eigen::Index i = 0; i < g.rows(); ++i)
        for (int c = 0; c < 3; ++c) g(i, c) *= 1 + e * (2 * rng.uniform() - 1);
      const MeasureEstimate m = measure_importance(p, r, dir, g, 0.1, 20000, 21, true);
      for (int c = 0; c < 3; ++c) {
        const std::string label = std::string(m.method) + " eps " + std::to_string(e) + " c" + std::to_string(c);
        means.add(label, m.M(c), m.se(c), M(c));
        CHECK(m.var_theory(c) < previous(c));  // the exact variance falls as the importance improves
      }
      previous = m.var_theory;
      // The sample variance against the exact one: its standard error from 20 runs' spread (as above).
      std::vector<PowerSums> v(3);
      for (int run = 0; run < 20; ++run) {
        const MeasureEstimate k = measure_importance(p, r, dir, g, 0.1, 2000, 200 + std::uint64_t(run), false);
        for (int c = 0; c < 3; ++c) v[std::size_t(c)].add(k.var(c));
      }
      for (int c = 0; c < 3; ++c)
        vars.add(std::string(m.method) + " eps " + std::to_string(e) + " c" + std::to_string(c),
                 v[std::size_t(c)].mean(), v[std::size_t(c)].standard_error(), m.var_theory(c));
    }
  }
  means.check();
  vars.check();
}

TEST_CASE("estimates of M do not depend on the thread count", "[measure]") {
  const RadiosityProblem p = test::mixed_cube();
  const Response r = sensor(6, {0, 3});
  WalkOptions o;
  o.method = WalkMethod::shoot_collision;
  MeasureEstimate one, two;
  {
    const ThreadLimit limit(1);
    one = measure_random_walk(p, nullptr, nullptr, o, r, 50000, false);
  }
  {
    const ThreadLimit limit(2);
    two = measure_random_walk(p, nullptr, nullptr, o, r, 50000, false);
  }
  for (int c = 0; c < 3; ++c) {
    CHECK(one.M(c) == two.M(c));
    CHECK(one.var(c) == two.var(c));
  }
}
