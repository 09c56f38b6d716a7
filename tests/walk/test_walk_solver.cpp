// Options, reproducibility (1 and 2 threads bit-identical), and the comparison table.
#include <catch2/catch.hpp>

#include "core/error.h"
#include "core/moments.h"
#include "core/parallel.h"
#include "visibility/brute_force_visibility.h"
#include "walk/matrix_kernel.h"
#include "walk/random_walk_solver.h"
#include "walk/walk_compare.h"
#include "walk/walk_variance.h"
#include "walk_test_scenes.h"

using namespace radwalk;

TEST_CASE("invalid options are InputErrors with a clear message", "[walk][options]") {
  const RadiosityProblem p = test::mixed_cube();
  auto fails = [&](WalkOptions o, const std::string& words) {
    try {
      solve_random_walk(p, nullptr, nullptr, o);
    } catch (const InputError& e) {
      INFO(e.what());
      CHECK(std::string(e.what()).find(words) != std::string::npos);
      return;
    }
    FAIL("no InputError for " << method_name(o) << " (expected '" << words << "')");
  };
  WalkOptions o;
  o.walk = "shoot";
  o.estimator = "expected-value";
  fails(o, "not available for shooting");
  o = WalkOptions();
  o.estimator = "survival";
  fails(o, "not available for gathering");
  o = WalkOptions();
  o.kernel = "bvh";
  fails(o, "kernel 'bvh'");
  o = WalkOptions();
  o.kernel = "ray";
  fails(o, "needs the patches");
  o = WalkOptions();
  o.patches = {6};
  fails(o, "patch 6 is out of range");
  o = WalkOptions();
  o.walks = 1;
  fails(o, "at least 2");
  o = WalkOptions();
  o.survival = "constant";
  o.survival_constant = 1.0;
  fails(o, "not in (0, 1)");
  o = WalkOptions();
  o.survival = "sometimes";
  fails(o, "unknown survival mode");
  CHECK_THROWS_AS(set_method(o, "gather-telepathy"), InputError);
}

TEST_CASE("1 and 2 threads give bit-identical results", "[walk][threads]") {
  const RadiosityProblem p = test::mixed_cube();
  const PatchSet patches = test::cube_patches(p);
  const BruteForceVisibility visibility(patches);
  for (const std::string kernel : {"matrix", "ray"})
    for (const std::string method : {"gather-expected-value", "shoot-collision"}) {
      WalkOptions o;
      set_method(o, method);
      o.kernel = kernel;
      o.walks = kernel == std::string("ray") ? 3000 : 30000;
      Solution one, two;
      {
        ThreadLimit limit(1);
        one = solve_random_walk(p, &patches, &visibility, o);
      }
      {
        ThreadLimit limit(2);
        two = solve_random_walk(p, &patches, &visibility, o);
      }
      INFO(kernel << " " << method);
      CHECK((one.B == two.B).all());
      CHECK((one.var == two.var).all());
      CHECK(one.steps == two.steps);
    }
}

TEST_CASE("walk w from patch i uses the stream (seed, gather_walk, i, w)", "[walk][threads]") {
  // The solver's estimate equals the mean of walks replayed one by one from their streams.
  const RadiosityProblem p = test::mixed_cube();
  WalkOptions o;
  o.estimator = "expected-value";
  o.walks = 3000;
  o.seed = 17;
  const Solution s = solve_random_walk(p, nullptr, nullptr, o);
  const MatrixKernel kernel(p, survival_probabilities(p.rho, "analog", 0));
  for (std::size_t i = 0; i < 6; ++i) {
    const auto x = test::gather_scores(GatherEstimator::expected_value, kernel, i, o.walks, o.seed);
    for (int c = 0; c < 3; ++c) {
      const SampleMoments m = sample_moments(x[c]);
      CHECK(s.B(static_cast<Eigen::Index>(i), c) == Approx(m.mean).epsilon(1e-12));
      CHECK(s.var(static_cast<Eigen::Index>(i), c) == Approx(m.var).epsilon(1e-9));
    }
  }
}

TEST_CASE("compare tabulates every method against the reference", "[walk][compare]") {
  const RadiosityProblem p = test::mixed_cube();
  CompareOptions o;
  o.runs = 3;
  o.walk.walks = 2000;
  const CompareResult r = compare_random_walks(p, nullptr, nullptr, o);
  CHECK(r.rows.size() == 6 * 6 * 3);
  REQUIRE(r.summary.size() == 6);
  for (const CompareSummary& s : r.summary) {
    INFO(s.method);
    CHECK(std::isfinite(s.mean_abs_z));
    CHECK(std::isfinite(s.var_ratio));
    CHECK(s.seconds > 0);
    CHECK(s.steps > 0);
  }
  CHECK(r.rows[0].walks == 6000);
  const std::string table = format_compare_summary(r.summary);
  for (const std::string& m : walk_methods()) CHECK(table.find(m) != std::string::npos);
}
