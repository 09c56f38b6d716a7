// Stochastic Jacobi (WalkSampler::jacobi, walk/stochastic_jacobi.h):
//   - unbiased: on the closed and the open unit cube (exact F) the mean of K = 40 independent solves passes a
//     t-test against the dense solve for every patch and channel (family-wise alpha = 1e-3, Sidak), on the ray
//     and matrix kernels, with and without the direct light as the first shot (the truncation at 1e-6 of the
//     power is far below these tests' resolution);
//   - the replicate standard errors cover: the 95 % t-interval (3 degrees of freedom) holds the exact B in a
//     fraction of 300 solves within the binomial tolerance of 0.95 (alpha = 1e-3, Sidak over the entries);
//   - 1 and 2 threads give bit-identical outputs; it is refused for other estimators than shoot-collision.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "support/stat_checks.h"
#include "visibility/brute_force_visibility.h"
#include "walk/random_walk_solver.h"
#include "walk/walk_variance.h"
#include "walk_test_scenes.h"

using namespace radwalk;

namespace {

// Student's t two-sided critical value at the level of the normal critical value z (Cornish-Fisher, nu >= 20).
double t_critical(double z, double nu) {
  const double z2 = z * z;
  return z + (z2 * z + z) / (4 * nu) + (5 * z2 * z2 * z + 16 * z2 * z + 3 * z) / (96 * nu * nu) +
         (3 * z2 * z2 * z2 * z + 19 * z2 * z2 * z + 17 * z2 * z - 15 * z) / (384 * nu * nu * nu);
}

WalkOptions jacobi_options(WalkKernel kernel, bool direct) {
  WalkOptions o;
  o.method = WalkMethod::shoot_collision;
  o.kernel = kernel;
  o.sampler = WalkSampler::jacobi;
  o.direct_light = direct;
  o.particles = 4000;
  o.shadow_rays = 256;
  return o;
}

}  // namespace

TEST_CASE("stochastic Jacobi is unbiased against the exact solutions of the closed and open cube",
          "[walk][jacobi]") {
  constexpr int K = 40;
  const std::vector<std::vector<int>> face_sets = {{0, 1, 2, 3, 4, 5}, {0, 1, 2, 3, 4}};
  struct Config {
    WalkKernel kernel;
    bool direct;
  };
  const std::vector<Config> configs = {
      {WalkKernel::ray, false}, {WalkKernel::ray, true}, {WalkKernel::matrix, false}, {WalkKernel::matrix, true}};
  const double t_crit = t_critical(z_critical(sidak(1e-3, face_sets.size() * configs.size() * 6 * 3)), K - 1);
  for (const auto& faces : face_sets) {
    const RadiosityProblem p = test::mixed_cube(faces);
    const PatchSet patches = test::cube_patches(p, faces);
    const BruteForceVisibility visibility(patches);
    const PatchRgb B = dense_radiosity(p);
    for (const Config& c : configs) {
      WalkOptions o = jacobi_options(c.kernel, c.direct);
      const auto N = Eigen::Index(patches.size());
      PatchRgb sum = PatchRgb::Zero(N, 3), sum2 = PatchRgb::Zero(N, 3);
      for (int k = 0; k < K; ++k) {
        o.seed = std::uint64_t(300 + k);
        const Solution s = solve_random_walk(p, &patches, &visibility, o);
        REQUIRE(s.status == SolveStatus::converged);
        sum += s.B;
        sum2 += s.B.square();
      }
      const PatchRgb mean = sum / K, se = ((sum2 / K - mean.square()) * (double(K) / (K - 1)) / K).max(0).sqrt();
      test::ZTable table(std::to_string(faces.size()) + " faces, " + std::string(kernel_name(c.kernel)) +
                             " jacobi" + (c.direct ? "+direct" : ""),
                         t_crit);
      for (Eigen::Index i = 0; i < N; ++i)
        for (int ch = 0; ch < 3; ++ch) table.add_patch(i, ch, "B", mean(i, ch), se(i, ch), B(i, ch));
      table.check(&patches);
    }
  }
}

TEST_CASE("stochastic Jacobi's replicate standard errors cover", "[walk][jacobi][coverage]") {
  const RadiosityProblem p = test::mixed_cube();
  const PatchSet patches = test::cube_patches(p);
  const BruteForceVisibility visibility(patches);
  const PatchRgb B = dense_radiosity(p);
  constexpr int kSolves = 300;
  constexpr double kT3 = 3.182446305284263;  // Student's t, 3 degrees of freedom, two-sided 95 %
  struct Entry {
    int i, c;
  };
  const std::vector<Entry> entries = {{1, 0}, {3, 1}, {5, 2}};
  std::vector<int> covered(entries.size(), 0);
  WalkOptions o = jacobi_options(WalkKernel::matrix, false);
  o.particles = 2000;
  for (int k = 0; k < kSolves; ++k) {
    o.seed = std::uint64_t(7000 + k);
    const Solution s = solve_random_walk(p, &patches, &visibility, o);
    for (std::size_t e = 0; e < entries.size(); ++e)
      covered[e] += std::abs(s.B(entries[e].i, entries[e].c) - B(entries[e].i, entries[e].c)) <=
                    kT3 * s.B_se(entries[e].i, entries[e].c);
  }
  const double z_crit = z_critical(sidak(1e-3, entries.size()));
  for (std::size_t e = 0; e < entries.size(); ++e)
    test::check_z("coverage of patch " + std::to_string(entries[e].i) + " channel " + std::to_string(entries[e].c),
                  double(covered[e]) / kSolves, test::binomial_se(0.95, kSolves), 0.95, z_crit);
}

TEST_CASE("stochastic Jacobi gives bit-identical results on 1 and 2 threads and is refused where it does not apply",
          "[walk][jacobi][threads]") {
  const RadiosityProblem p = test::mixed_cube();
  const PatchSet patches = test::cube_patches(p);
  const BruteForceVisibility visibility(patches);
  for (const bool direct : {false, true}) {
    WalkOptions o = jacobi_options(WalkKernel::ray, direct);
    o.particles = 50000;
    Solution one, two;
    {
      ThreadLimit limit(1);
      one = solve_random_walk(p, &patches, &visibility, o);
    }
    {
      ThreadLimit limit(2);
      two = solve_random_walk(p, &patches, &visibility, o);
    }
    INFO("direct light " << direct);
    CHECK((one.B == two.B).all());
    CHECK((one.B_se == two.B_se).all());
    CHECK(one.steps == two.steps);
  }
  WalkOptions o = jacobi_options(WalkKernel::ray, false);
  o.method = WalkMethod::shoot_absorption;
  CHECK_THROWS_WITH(check_walk_options(o, 6), Catch::Contains("--sampler jacobi"));
  o.method = WalkMethod::gather_collision;
  CHECK_THROWS_AS(check_walk_options(o, 6), InputError);
}
