// The Sobol sampler of the shooting methods (WalkSampler::sobol: core/sobol.h, walk/stratified_emission.h,
// walk/direct_light.h, random_walk_solver.h):
//   - the points keep their stratification: dimensions (0, 1) are a (0, 2)-sequence in base 2 (every elementary
//     interval of area 2^-m holds exactly one of 2^m aligned consecutive points), every dimension a
//     (0, 1)-sequence, with and without a digital shift;
//   - stratified emission gives every source patch floor or ceil of n pi_j particles;
//   - the estimates are unbiased: on the unit cube and on two opposed squares (exact F) the mean of K independent
//     solves passes a t-test against the dense solve for every patch and channel (family-wise alpha = 1e-3,
//     Sidak), for the ray and matrix kernels, with and without the direct light computed apart (by shadow rays
//     only on the two squares: see two_squares), closed and open cube; the shadow-ray direct light alone is
//     unbiased for rho F E;
//   - the replicate standard errors are honest: the 95 % t-interval (R - 1 degrees of freedom) covers the exact
//     B in a fraction of many seeded solves within the binomial tolerance of 0.95 (alpha = 1e-3, Sidak);
//   - 1 and 2 threads give bit-identical outputs; the options that do not apply are refused.
#include <catch2/catch.hpp>

#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "core/sobol.h"
#include "patch/patch_builder.h"
#include "support/stat_checks.h"
#include "support/view_factors.h"
#include "visibility/brute_force_visibility.h"
#include "walk/direct_light.h"
#include "walk/random_walk_solver.h"
#include "walk/stratified_emission.h"
#include "walk/walk_variance.h"
#include "walk_test_scenes.h"

using namespace radwalk;

namespace {

// The two-sided critical value of Student's t with nu degrees of freedom at the level of z (two-sided normal
// critical value z): the Cornish-Fisher expansion t = z + (z^3 + z) / (4 nu) + (5 z^5 + 16 z^3 + 3 z) / (96 nu^2)
// + (3 z^7 + 19 z^5 + 17 z^3 - 15 z) / (384 nu^3), within 1e-3 of the exact quantile for nu >= 20 at z <= 5.
double t_critical(double z, double nu) {
  const double z2 = z * z;
  return z + (z2 * z + z) / (4 * nu) + (5 * z2 * z2 * z + 16 * z2 * z + 3 * z) / (96 * nu * nu) +
         (3 * z2 * z2 * z2 * z + 19 * z2 * z2 * z + 17 * z2 * z - 15 * z) / (384 * nu * nu * nu);
}

// Two directly opposed unit squares at distance 0.5 (an open scene): the floor (patch 0, rho = (0.6, 0.5, 0.4),
// facing up) and an emitting ceiling (patch 1, E = (2, 1, 0.5), rho = (0.3, 0.2, 0.1), facing down), with the
// exact F of formula C-11 (view_factors.h). The emitter shares no edge with a receiver, so the shadow-ray direct
// light has a finite variance (it has not on receivers sharing an edge with an emitter at an angle below 180
// degrees: the cube's walls, where G ~ 1 / r^2 at the edge makes E[G^2] diverge).
struct TwoSquares {
  PatchSet patches;
  RadiosityProblem problem;
};
TwoSquares two_squares() {
  constexpr double c = 0.5;
  PatchBuilder b;
  const int floor = b.add_material("floor", Rgb(0.6, 0.5, 0.4));
  const int light = b.add_material("light", Rgb(0.3, 0.2, 0.1), Rgb(2, 1, 0.5) / kPi);
  b.add_quad(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), floor);
  b.add_quad(Vec3(0, 0, c), Vec3(0, 1, c), Vec3(1, 1, c), Vec3(1, 0, c), light);
  TwoSquares t{b.build(), {}};
  const double F = test::parallel_rectangles(1, 1, c);
  SparseF Fm(2, 2);
  Fm.insert(0, 1) = static_cast<float>(F);
  Fm.insert(1, 0) = static_cast<float>(F);
  t.problem = make_problem(t.patches, Fm);
  return t;
}

std::vector<float> coordinates(std::uint32_t first, std::uint32_t count, int d, const SobolShift& shift) {
  std::vector<float> x;
  for (std::uint32_t r = first; r < first + count; ++r) x.push_back(sobol_point(r, shift)[std::size_t(d)]);
  return x;
}

}  // namespace

TEST_CASE("Sobol dimensions 0 and 1 are a (0, 2)-sequence and every dimension a (0, 1)-sequence",
          "[walk][sobol]") {
  Rng rng = stream(1, StreamDomain::test, 14, 0);
  SobolShift shifted;
  for (auto& w : shifted.word) w = rng.next_u32();
  for (const SobolShift& shift : {SobolShift{}, shifted}) {
    for (int m = 0; m <= 10; ++m) {
      const std::uint32_t n = 1u << m;
      for (std::uint32_t q = 0; q < 3; ++q) {
        const std::vector<float> x = coordinates(q * n, n, 0, shift), y = coordinates(q * n, n, 1, shift);
        // Elementary intervals 2^-i x 2^-(m-i): each holds exactly one point.
        for (int i = 0; i <= m; ++i) {
          std::set<std::uint64_t> cells;
          for (std::uint32_t k = 0; k < n; ++k)
            cells.insert(std::uint64_t(std::ldexp(x[k], i)) << 32 | std::uint64_t(std::ldexp(y[k], m - i)));
          INFO("m = " << m << ", block " << q << ", intervals 2^-" << i << " x 2^-" << m - i);
          CHECK(cells.size() == n);
        }
        for (int d = 0; d < kSobolDimensions; ++d) {
          std::set<std::uint64_t> cells;
          for (float u : coordinates(q * n, n, d, shift)) cells.insert(std::uint64_t(std::ldexp(u, m)));
          INFO("dimension " << d << ", m = " << m);
          CHECK(cells.size() == n);
        }
      }
    }
  }
  // Dimensions 2 and 3 are not copies of 0 and 1 (their direction numbers differ), and coordinates lie in [0, 1).
  CHECK(sobol_u32(3, 2) != sobol_u32(3, 0));
  CHECK(sobol_u32(5, 3) != sobol_u32(5, 1));
  for (std::uint32_t r = 0; r < 4096; ++r)
    for (int d = 0; d < kSobolDimensions; ++d) CHECK((sobol_point(r, shifted)[std::size_t(d)] < 1.0f));
}

TEST_CASE("stratified emission gives each source patch floor or ceil of n pi_j particles", "[walk][sobol]") {
  PatchRgb S(5, 3);
  S << 1, 2, 3, 0, 0, 0, 0.5, 0.1, 0.2, 4, 0, 0, 0, 0, 0;
  const Eigen::VectorXd area = (Eigen::VectorXd(5) << 1, 2, 3, 0.5, 1).finished();
  double phi_total = 0;
  for (int j = 0; j < 5; ++j) phi_total += area(j) * S.row(j).sum();
  for (std::uint64_t seed : {1, 2, 3})
    for (long n : {1L, 7L, 1000L, 12345L}) {
      const StratifiedEmission em(S, area, n, seed, 0);
      long total = 0;
      for (std::size_t j = 0; j < 5; ++j) {
        const long count = em.first()[j + 1] - em.first()[j];
        const double expected = double(n) * area(Eigen::Index(j)) * S.row(Eigen::Index(j)).sum() / phi_total;
        INFO("patch " << j << ", n = " << n << ", seed " << seed);
        CHECK(count >= std::floor(expected));
        CHECK(count <= std::ceil(expected));
        total += count;
        for (long w = em.first()[j]; w < em.first()[j + 1]; ++w) CHECK(em.patch_of(w) == j);
      }
      CHECK(total == n);
    }
  // A signed source (the direct light's unbiased estimate can be negative in full shadow): births by |S|, the
  // weights keep the sign.
  const StratifiedEmission plus(S, area, 100, 1, 0), minus(-S, area, 100, 1, 0);
  CHECK(plus.first() == minus.first());
  for (std::size_t j = 0; j < 5; ++j) CHECK((minus.weight(j) == -plus.weight(j)).all());
  PatchRgb bad = S;
  bad(2, 1) = std::nan("");
  CHECK_THROWS_AS(StratifiedEmission(bad, area, 10, 1, 0), InputError);
  CHECK_THROWS_AS(StratifiedEmission(S, -area, 10, 1, 0), InputError);
}

TEST_CASE("the Sobol sampler is unbiased against the exact solutions of the cube and the two squares", "[walk][sobol][ray]") {
  constexpr int K = 40;  // independent solves (seeds) per configuration
  const std::vector<std::vector<int>> face_sets = {{0, 1, 2, 3, 4, 5}, {0, 1, 2, 3, 4}};
  struct Config {
    WalkKernel kernel;
    WalkMethod method;
    bool direct;
    bool sampled = false;  // the direct light by point-to-point shadow rays (else point-to-polygon x visibility)
  };
  // The cube (emitters sharing edges with receivers: the direct light apart only exact where unoccluded, the
  // point-to-point shadow rays' variance is infinite there, see two_squares) and the two squares.
  const std::vector<Config> cube_configs = {{WalkKernel::ray, WalkMethod::shoot_collision, false},
                                            {WalkKernel::ray, WalkMethod::shoot_absorption, false},
                                            {WalkKernel::ray, WalkMethod::shoot_collision, true},
                                            {WalkKernel::matrix, WalkMethod::shoot_collision, true}};
  const std::vector<Config> squares_configs = {{WalkKernel::ray, WalkMethod::shoot_collision, false},
                                               {WalkKernel::ray, WalkMethod::shoot_collision, true},
                                               {WalkKernel::ray, WalkMethod::shoot_collision, true, true},
                                               {WalkKernel::ray, WalkMethod::shoot_absorption, true},
                                               {WalkKernel::ray, WalkMethod::shoot_survival, true}};
  const double t_crit = t_critical(
      z_critical(sidak(1e-3, (face_sets.size() * cube_configs.size() * 6 + squares_configs.size() * 2) * 3)), K - 1);
  const TwoSquares squares = two_squares();
  for (std::size_t scene = 0; scene < face_sets.size() + 1; ++scene) {
    const bool cube = scene < face_sets.size();
    const std::vector<int> faces = cube ? face_sets[scene] : std::vector<int>{};
    const RadiosityProblem p = cube ? test::mixed_cube(faces) : squares.problem;
    const PatchSet patches = cube ? test::cube_patches(p, faces) : squares.patches;
    const BruteForceVisibility visibility(patches);
    const std::vector<Config>& configs = cube ? cube_configs : squares_configs;
    const PatchRgb B = dense_radiosity(p);
    for (const Config& c : configs) {
      WalkOptions o;
      o.method = c.method;
      o.kernel = c.kernel;
      o.sampler = WalkSampler::sobol;
      o.direct_light = c.direct;
      o.direct_sampled = c.sampled;
      o.particles = 4000;
      o.shadow_rays = 256;
      const auto N = Eigen::Index(patches.size());
      PatchRgb sum = PatchRgb::Zero(N, 3), sum2 = PatchRgb::Zero(N, 3);
      for (int k = 0; k < K; ++k) {
        o.seed = std::uint64_t(100 + k);
        const Solution s = solve_random_walk(p, &patches, &visibility, o);
        REQUIRE(s.status == SolveStatus::converged);
        sum += s.B;
        sum2 += s.B.square();
      }
      const PatchRgb mean = sum / K, se = ((sum2 / K - mean.square()) * (double(K) / (K - 1)) / K).max(0).sqrt();
      test::ZTable table((cube ? std::to_string(faces.size()) + " faces, " : std::string("two squares, ")) +
                             std::string(kernel_name(c.kernel)) + " " +
                             std::string(method_name(c.method)) +
                             (c.direct ? (c.sampled ? " sobol+direct (shadow rays)" : " sobol+direct") : " sobol"),
                         t_crit);
      for (Eigen::Index i = 0; i < N; ++i)
        for (int ch = 0; ch < 3; ++ch) table.add_patch(i, ch, "B", mean(i, ch), se(i, ch), B(i, ch));
      table.check(&patches);
    }
  }
}

TEST_CASE("the direct light by shadow rays is unbiased for rho F E on the two squares", "[walk][sobol][ray]") {
  const TwoSquares squares = two_squares();
  const RadiosityProblem& p = squares.problem;
  const PatchSet& patches = squares.patches;
  const BruteForceVisibility visibility(patches);
  const PatchRgb D = exact_direct_light(p);
  CHECK(D(0, 0) > 0);
  CHECK(D(1, 0) == 0);  // the light receives nothing from itself
  constexpr int K = 40;
  PatchRgb sum = PatchRgb::Zero(2, 3), sum2 = PatchRgb::Zero(2, 3);
  for (int k = 0; k < K; ++k) {
    const DirectLight d = estimate_direct_light(p, patches, visibility, 64, 7, std::uint64_t(k));
    CHECK(d.rays > 0);
    sum += d.D;
    sum2 += d.D.square();
  }
  const PatchRgb mean = sum / K, se = ((sum2 / K - mean.square()) * (double(K) / (K - 1)) / K).max(0).sqrt();
  test::ZTable table("direct light, 64 Sobol shadow rays per patch", t_critical(z_critical(sidak(1e-3, 6)), K - 1),
                     test::ZeroVariance::exact);
  for (Eigen::Index i = 0; i < 2; ++i)
    for (int ch = 0; ch < 3; ++ch) table.add_patch(i, ch, "D", mean(i, ch), se(i, ch), D(i, ch));
  table.check(&patches);
}

TEST_CASE("the direct light exact where unoccluded is unbiased for rho F E on the two squares and the cube",
          "[walk][sobol][ray]") {
  const TwoSquares squares = two_squares();
  const RadiosityProblem cube = test::mixed_cube();
  const PatchSet cube_patches = test::cube_patches(cube);
  constexpr int K = 40;
  const double t_crit = t_critical(z_critical(sidak(1e-3, (2 + 6) * 3)), K - 1);
  for (const bool on_cube : {false, true}) {
    const RadiosityProblem& p = on_cube ? cube : squares.problem;
    const PatchSet& patches = on_cube ? cube_patches : squares.patches;
    const BruteForceVisibility visibility(patches);
    const PatchRgb D = exact_direct_light(p);
    const auto N = Eigen::Index(patches.size());
    PatchRgb sum = PatchRgb::Zero(N, 3), sum2 = PatchRgb::Zero(N, 3);
    for (int k = 0; k < K; ++k) {
      const DirectLight d = estimate_visible_direct_light(p, patches, visibility, 32, 7, std::uint64_t(k));
      CHECK(d.rays > 0);
      sum += d.D;
      sum2 += d.D.square();
    }
    const PatchRgb mean = sum / K, se = ((sum2 / K - mean.square()) * (double(K) / (K - 1)) / K).max(0).sqrt();
    test::ZTable table(std::string(on_cube ? "cube" : "two squares") + ": direct light, 32 samples per patch",
                       t_crit, test::ZeroVariance::exact);
    for (Eigen::Index i = 0; i < N; ++i)
      for (int ch = 0; ch < 3; ++ch) table.add_patch(i, ch, "D", mean(i, ch), se(i, ch), D(i, ch));
    table.check(&patches);
  }
}

TEST_CASE("replicate standard errors cover: the 95 % interval holds the exact B in 95 % of solves",
          "[walk][sobol][coverage]") {
  const TwoSquares squares = two_squares();
  const RadiosityProblem cube = test::mixed_cube();
  const PatchSet cube_patches = test::cube_patches(cube);
  constexpr int kSolves = 300, R = 4;
  constexpr double kT3 = 3.182446305284263;  // Student's t, 3 degrees of freedom, two-sided 95 %
  // (scene, patch, channel): the cube without the direct light apart, the two squares' floor with it.
  struct Entry {
    bool cube;
    int i, c;
  };
  const std::vector<Entry> entries = {{true, 1, 0}, {true, 3, 1}, {true, 5, 2}, {false, 0, 0}, {false, 0, 2}};
  std::vector<int> covered(entries.size(), 0);
  for (const bool on_cube : {true, false}) {
    const RadiosityProblem& p = on_cube ? cube : squares.problem;
    const PatchSet& patches = on_cube ? cube_patches : squares.patches;
    const BruteForceVisibility visibility(patches);
    const PatchRgb B = dense_radiosity(p);
    WalkOptions o;
    o.method = WalkMethod::shoot_collision;
    o.kernel = WalkKernel::ray;
    o.sampler = WalkSampler::sobol;
    o.direct_light = !on_cube;
    o.replicates = R;
    o.particles = 2000;
    o.shadow_rays = 64;
    for (int k = 0; k < kSolves; ++k) {
      o.seed = std::uint64_t(5000 + k);
      const Solution s = solve_random_walk(p, &patches, &visibility, o);
      for (std::size_t e = 0; e < entries.size(); ++e) {
        if (entries[e].cube != on_cube) continue;
        const int i = entries[e].i, c = entries[e].c;
        covered[e] += std::abs(s.B(i, c) - B(i, c)) <= kT3 * s.B_se(i, c);
      }
    }
  }
  const double z_crit = z_critical(sidak(1e-3, entries.size()));
  for (std::size_t e = 0; e < entries.size(); ++e)
    test::check_z(std::string(entries[e].cube ? "cube" : "two squares") + ": coverage of patch " +
                      std::to_string(entries[e].i) + " channel " + std::to_string(entries[e].c),
                  double(covered[e]) / kSolves, test::binomial_se(0.95, kSolves), 0.95, z_crit);
}

TEST_CASE("the Sobol sampler gives bit-identical results on 1 and 2 threads", "[walk][sobol][threads]") {
  const RadiosityProblem p = test::mixed_cube();
  const PatchSet patches = test::cube_patches(p);
  const BruteForceVisibility visibility(patches);
  for (const bool direct : {false, true}) {
    WalkOptions o;
    o.method = WalkMethod::shoot_collision;
    o.kernel = WalkKernel::ray;
    o.sampler = WalkSampler::sobol;
    o.direct_light = direct;
    o.particles = 20000;
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
}

TEST_CASE("sampler options that do not apply are refused", "[walk][sobol][options]") {
  WalkOptions o;
  o.method = WalkMethod::gather_collision;
  o.sampler = WalkSampler::sobol;
  CHECK_THROWS_WITH(check_walk_options(o, 6), Catch::Contains("for shooting methods"));
  o.method = WalkMethod::shoot_collision;
  o.sampler = WalkSampler::random;
  o.direct_light = true;
  CHECK_THROWS_WITH(check_walk_options(o, 6), Catch::Contains("needs --sampler sobol"));
  o.sampler = WalkSampler::sobol;
  o.replicates = 1;
  CHECK_THROWS_WITH(check_walk_options(o, 6), Catch::Contains("--replicates"));
  o.replicates = 4;
  CHECK_NOTHROW(check_walk_options(o, 6));
  CHECK(parse_walk_sampler("sobol") == WalkSampler::sobol);
  CHECK_THROWS_AS(parse_walk_sampler("halton"), InputError);
}
