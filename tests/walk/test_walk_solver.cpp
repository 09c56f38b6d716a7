// Options, reproducibility (1 and 2 threads bit-identical), and the comparison table.
#include <catch2/catch.hpp>

#include <algorithm>

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
  auto fails = [&](auto&& f, const std::string& words) {
    try {
      f();
    } catch (const InputError& e) {
      INFO(e.what());
      CHECK(std::string(e.what()).find(words) != std::string::npos);
      return;
    }
    FAIL("no InputError (expected '" << words << "')");
  };
  auto solve = [&](const WalkOptions& o) { return [&p, o] { solve_random_walk(p, nullptr, nullptr, o); }; };
  // Names: parsed in one place each, with the valid choices and the nearest.
  fails([] { walk_method(WalkDirection::shoot, "expected-value"); }, "not available for shooting");
  fails([] { walk_method(WalkDirection::gather, "survival"); }, "not available for gathering");
  fails([] { parse_walk_kernel("bvh"); }, "kernel 'bvh'");
  fails([] { parse_survival_rule("sometimes"); }, "unknown survival mode");
  fails([] { parse_walk_method("gather-colision"); }, "did you mean 'gather-collision'?");
  fails([] { walk_method(WalkDirection::gather, "colision"); }, "did you mean 'collision'?");
  CHECK_THROWS_AS(parse_walk_method("gather-telepathy"), InputError);
  // Values.
  WalkOptions o;
  o.kernel = WalkKernel::ray;
  CHECK_THROWS_AS(solve(o)(), InternalError);  // a caller's bug: the ray kernel needs the patches
  o = WalkOptions();
  o.patches = {6};
  fails(solve(o), "patch 6 is out of range");
  o = WalkOptions();
  o.walks_per_patch = 1;
  fails(solve(o), "at least 2");
  o = WalkOptions();
  o.method = WalkMethod::shoot_collision;
  o.particles = 1;
  fails(solve(o), "at least 2");
  o = WalkOptions();
  o.survival = {SurvivalRule::constant, 1.0};
  fails(solve(o), "not in (0, 1)");
}

TEST_CASE("the method table names every method once and parses its own names", "[walk][options]") {
  std::vector<std::string> names;
  for (const WalkMethodRow& row : kWalkMethods) {
    INFO(row.name);
    CHECK(parse_walk_method(row.name) == row.method);
    CHECK(walk_method(row.direction, row.estimator) == row.method);
    CHECK(method_name(row.method) == row.name);
    CHECK(row.name == std::string(direction_name(row.direction)) + "-" + std::string(row.estimator));
    names.emplace_back(row.name);
  }
  CHECK(names == walk_method_names());
  std::sort(names.begin(), names.end());
  CHECK(std::adjacent_find(names.begin(), names.end()) == names.end());
  // The CLI's default and the library's agree on gathering collision.
  CHECK(WalkOptions().method == WalkMethod::gather_collision);
}

TEST_CASE("1 and 2 threads give bit-identical results", "[walk][threads]") {
  const RadiosityProblem p = test::mixed_cube();
  const PatchSet patches = test::cube_patches(p);
  const BruteForceVisibility visibility(patches);
  for (const WalkKernel kernel : {WalkKernel::matrix, WalkKernel::ray})
    for (const WalkMethod method : {WalkMethod::gather_expected_value, WalkMethod::shoot_collision}) {
      WalkOptions o;
      o.method = method;
      o.kernel = kernel;
      o.walks_per_patch = o.particles = kernel == WalkKernel::ray ? 3000 : 30000;
      Solution one, two;
      {
        ThreadLimit limit(1);
        one = solve_random_walk(p, &patches, &visibility, o);
      }
      {
        ThreadLimit limit(2);
        two = solve_random_walk(p, &patches, &visibility, o);
      }
      INFO(kernel_name(kernel) << " " << method_name(method));
      CHECK((one.B == two.B).all());
      CHECK((one.var == two.var).all());
      CHECK(one.steps == two.steps);
    }
}

TEST_CASE("walk w from patch i uses the stream (seed, gather_walk, i, w)", "[walk][threads]") {
  // The solver's estimate equals the mean of walks replayed one by one from their streams.
  const RadiosityProblem p = test::mixed_cube();
  WalkOptions o;
  o.method = WalkMethod::gather_expected_value;
  o.walks_per_patch = 3000;
  o.seed = 17;
  const Solution s = solve_random_walk(p, nullptr, nullptr, o);
  const MatrixKernel kernel(p, survival_probabilities(p.rho, {}));
  for (std::size_t i = 0; i < 6; ++i) {
    const auto x = test::gather_scores(WalkMethod::gather_expected_value, kernel, i, o.walks_per_patch, o.seed);
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
  o.walk.walks_per_patch = 2000;
  const CompareResult r = compare_random_walks(p, nullptr, nullptr, o);
  CHECK(r.rows.size() == kWalkMethods.size() * 6 * 3);
  REQUIRE(r.summary.size() == kWalkMethods.size());
  for (const CompareSummary& s : r.summary) {
    INFO(method_name(s.method));
    CHECK(std::isfinite(s.mean_abs_z));
    CHECK(std::isfinite(s.var_ratio));
    CHECK(s.seconds > 0);
    CHECK(s.steps > 0);
  }
  CHECK(r.rows[0].walks == 6000);
  const std::string table = format_compare_summary(r.summary);
  for (const std::string& m : walk_method_names()) CHECK(table.find(m) != std::string::npos);
}

TEST_CASE("compare's var_se is the spread of the runs' per-walk variances over sqrt(R)", "[walk][compare]") {
  const RadiosityProblem p = test::mixed_cube();
  CompareOptions o;
  o.methods = {WalkMethod::gather_collision, WalkMethod::shoot_collision};
  o.runs = 4;
  o.walk.walks_per_patch = 500;
  o.walk.seed = 11;
  const CompareResult r = compare_random_walks(p, nullptr, nullptr, o);
  for (const WalkMethod method : o.methods) {
    // The same runs by hand: run k has seed 11 + k and, shooting, walks_per_patch x patches particles.
    WalkOptions w = o.walk;
    w.method = method;
    w.particles = o.walk.walks_per_patch * static_cast<long>(p.size());
    std::vector<PatchRgb> vars;
    for (int k = 0; k < o.runs; ++k) {
      w.seed = o.walk.seed + static_cast<std::uint64_t>(k);
      vars.push_back(solve_random_walk(p, nullptr, nullptr, w).var);
    }
    for (const CompareRow& row : r.rows) {
      if (row.method != method) continue;
      double m = 0, m2 = 0;
      for (const PatchRgb& v : vars) {
        m += v(row.patch, row.channel) / o.runs;
        m2 += v(row.patch, row.channel) * v(row.patch, row.channel) / o.runs;
      }
      INFO(method_name(method) << " patch " << row.patch << " channel " << row.channel);
      CHECK(row.var == Approx(m).epsilon(1e-12));
      CHECK(row.var_se == Approx(std::sqrt(std::max(0.0, m2 - m * m) / (o.runs - 1))).epsilon(1e-9).margin(1e-300));
    }
  }
  o.runs = 1;
  for (const CompareRow& row : compare_random_walks(p, nullptr, nullptr, o).rows) CHECK(std::isnan(row.var_se));
}
