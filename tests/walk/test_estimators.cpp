// Every estimator is unbiased: z-tests against the dense solve of the same F, family-wise alpha = 1e-3 (Sidak over
// scenes x methods x patches x channels), on closed and open cubes, a row summing above 1, and non-analog
// survival. And the test rejects a deliberately biased estimator.
#include <catch2/catch.hpp>

#include "core/moments.h"
#include "support/stat_checks.h"
#include "walk/gather_estimators.h"
#include "walk/matrix_kernel.h"
#include "walk/random_walk_solver.h"
#include "walk/walk_variance.h"
#include "walk_test_scenes.h"

using namespace radwalk;

namespace {

struct Scene {
  std::string name;
  RadiosityProblem problem;
  Survival survival;
};

std::vector<Scene> scenes() {
  std::vector<Scene> s;
  s.push_back({"closed cube, analog", test::mixed_cube(), {SurvivalRule::analog}});
  s.push_back({"open cube (5 faces), analog", test::mixed_cube({0, 1, 2, 3, 4}), {SurvivalRule::analog}});
  Scene over{"closed cube, row 0 sums to 1.05, survival max", test::mixed_cube(), {SurvivalRule::max}};
  for (SparseF::InnerIterator it(over.problem.F, 0); it; ++it) it.valueRef() *= 1.05f;
  s.push_back(over);
  s.push_back({"closed cube, survival constant 0.7", test::mixed_cube(), {SurvivalRule::constant, 0.7}});
  Scene areas{"closed cube, areas 1..6 (F not reciprocal), analog", test::mixed_cube(), {SurvivalRule::analog}};
  areas.problem.area << 1, 2, 3, 4, 5, 6;
  s.push_back(areas);
  return s;
}

}  // namespace

TEST_CASE("every estimator is unbiased on the matrix kernel", "[walk][unbiased]") {
  const std::vector<Scene> all = scenes();
  std::size_t checks = 0;
  for (const Scene& s : all) checks += kWalkMethods.size() * s.problem.size() * 3;
  const double z_crit = z_critical(sidak(1e-3, checks));
  int rejected = 0;
  for (const Scene& s : all) {
    const PatchRgb B = dense_radiosity(s.problem);
    for (const WalkMethod method : all_walk_methods()) {
      const std::string name(method_name(method));
      WalkOptions o;
      o.method = method;
      o.walks_per_patch = 100000;
      o.particles = 600000;
      o.seed = 42;
      o.survival = s.survival;
      const Solution sol = solve_random_walk(s.problem, nullptr, nullptr, o);
      CHECK(sol.method == name);
      CHECK(sol.info.at("variance_radius") < 1);
      rejected += test::count_rejections(sol, B, z_crit, s.name + ", " + name);
    }
  }
  CHECK(rejected == 0);
}

TEST_CASE("gathering on a subset estimates only the chosen patches", "[walk][unbiased]") {
  const RadiosityProblem p = test::mixed_cube();
  WalkOptions o;
  o.method = WalkMethod::gather_collision;
  o.patches = {2, 4};
  o.walks_per_patch = 5000;
  const Solution sol = solve_random_walk(p, nullptr, nullptr, o);
  CHECK(sol.walks == 10000);
  for (Eigen::Index i = 0; i < 6; ++i) CHECK(std::isnan(sol.B(i, 0)) == (i != 2 && i != 4));
  CHECK(test::count_rejections(sol, dense_radiosity(p), z_critical(sidak(1e-3, 6)), "subset") == 0);
}

TEST_CASE("the z-test rejects a deliberately biased estimator", "[walk][unbiased]") {
  // Absorption that forgets to divide by the stop probability q: E[X] = sum_m (H^m diag(q) E) != B.
  const RadiosityProblem p = test::mixed_cube();
  const MatrixKernel kernel(p, survival_probabilities(p.rho, {}));
  const long walks = 20000;
  Solution biased;
  biased.B.setZero(6, 3);
  biased.B_se.setZero(6, 3);
  const KernelTables& t = kernel.tables();
  const std::vector<Rgb> weight = GatherWeights(t).w;
  for (std::size_t i = 0; i < 6; ++i) {
    Moments m;
    WalkCounters counters;
    for (long w = 0; w < walks; ++w) {
      Rng rng = stream(42, StreamDomain::test, i, static_cast<std::uint64_t>(w));
      std::size_t k = i;
      Rgb W = Rgb::Ones(), X = Rgb::Zero();
      for (;;) {
        if (rng.uniform() >= t.p[k]) {
          X = W * t.E[k];  // missing / q_k
          break;
        }
        const PatchIndex j = kernel.sample(k, rng, counters);
        if (j < 0) break;
        W *= weight[k];
        k = static_cast<std::size_t>(j);
      }
      m.add(X);
    }
    biased.B.row(static_cast<Eigen::Index>(i)) = m.mean.transpose();
    biased.B_se.row(static_cast<Eigen::Index>(i)) = m.standard_error().transpose();
  }
  const int rejected =
      test::count_rejections(biased, dense_radiosity(p), z_critical(sidak(1e-3, 18)), "biased", false);
  INFO("rejected " << rejected << " of 18 (patch, channel) entries of the biased estimator");
  CHECK(rejected >= 6);
}
