// The ray kernel (no stored F) agrees with the exact solution on the unit cube, whose exact form factors are
// known: every method's estimate passes a z-test against the dense solve with the analytic F (family-wise
// alpha = 1e-3, Sidak over scenes x methods x patches x channels); the form-factor error of the analytic F stored
// in float (1e-8) is far below the Monte Carlo error. Closed cube and an open cube (one face missing: escapes).
// Walks advanced in lockstep batches (walk_lockstep.h) score bit-identically to walks run one at a time, for both
// kernels and both visibilities. The ray kernel's single-precision rays match spawn_ray's in double for the
// same uniforms, and unit_circle (its cos/sin) is checked against std::cos/std::sin.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <utility>

#include "core/moments.h"
#include "core/sampling.h"
#include "patch/patch_builder.h"
#include "support/stat_checks.h"
#include "visibility/brute_force_visibility.h"
#include "visibility/embree_visibility.h"
#include "visibility/ray_offset.h"
#include "walk/matrix_kernel.h"
#include "walk/random_walk_solver.h"
#include "walk/ray_kernel.h"
#include "walk/walk_estimators.h"
#include "walk/walk_lockstep.h"
#include "walk/walk_variance.h"
#include "walk_test_scenes.h"

using namespace radwalk;

TEST_CASE("ray kernel agrees with the exact solution of the cube", "[walk][ray]") {
  const std::vector<std::vector<int>> face_sets = {{0, 1, 2, 3, 4, 5}, {0, 1, 2, 3, 4}};
  const double z_crit = z_critical(sidak(1e-3, 2 * kWalkMethods.size() * 6 * 3));
  int rejected = 0;
  for (const auto& faces : face_sets) {
    const RadiosityProblem p = test::mixed_cube(faces);
    const PatchSet patches = test::cube_patches(p, faces);
    for (std::size_t k = 0; k < patches.size(); ++k) CHECK(patches.normal[k].dot(Vec3(0.5, 0.5, 0.5) - patches.centroid[k]) > 0);
    const BruteForceVisibility visibility(patches);
    const PatchRgb B = dense_radiosity(p);
    RadiosityProblem no_F = p;
    no_F.F = SparseF();  // the ray kernel must not need F
    for (const WalkMethod method : all_walk_methods()) {
      WalkOptions o;
      o.method = method;
      o.kernel = WalkKernel::ray;
      o.walks_per_patch = 20000;
      o.particles = 120000;
      o.seed = 3;
      const Solution s = solve_random_walk(no_F, &patches, &visibility, o);
      rejected += test::count_rejections(
          s, B, z_crit, std::to_string(faces.size()) + " faces, ray " + std::string(method_name(method)), true,
          &patches);
      CHECK(s.info.at("back_hits") == 0);
      if (faces.size() == 6) CHECK(s.info.at("escapes") == 0);  // watertight: no ray leaks
      if (faces.size() == 5) CHECK(s.info.at("escapes") > 0);
      CHECK(std::isnan(s.info.at("variance_radius")));
    }
  }
  CHECK(rejected == 0);
}

TEST_CASE("ray kernel counts back-face hits and ends the walk there", "[walk][ray]") {
  // Face 5 turned around (normal outwards): rays from inside that reach it hit its back.
  RadiosityProblem p = test::mixed_cube();
  PatchSet patches = test::cube_patches(p);
  auto& c = patches.corners[5];
  std::swap(c[1], c[3]);
  compute_patch_geometry(patches);
  const BruteForceVisibility visibility(patches);
  WalkOptions o;
  o.kernel = WalkKernel::ray;
  o.method = WalkMethod::gather_collision;
  o.walks_per_patch = 2000;
  o.patches = {0, 1, 2, 3, 4};  // walks from face 5 itself would leave through its (outward) front
  const Solution s = solve_random_walk(p, &patches, &visibility, o);
  CHECK(s.info.at("back_hits") > 0);
  CHECK(s.info.at("escapes") == 0);
}

namespace {

// Per-walk gathering scores of patch i, walks 0..walks-1 from the streams stream(seed, StreamDomain::gather_walk, i, w), `lanes` at a time in
// lockstep (run_lockstep, as the solver runs them).
template <class K>
std::vector<Rgb> lockstep_gather_scores(WalkMethod method, const K& kernel, std::size_t i, std::size_t walks,
                                        std::uint64_t seed, std::size_t lanes, WalkCounters& counters) {
  std::vector<Rgb> X(walks, Rgb::Constant(-1.0));
  with_estimator_tables(method, kernel, [&](auto m, const auto& tables) {
    if constexpr (decltype(m)::kDirection == WalkDirection::gather) {
      using Walk = typename decltype(m)::Estimator::template Walk<K>;
      run_lockstep(
          kernel, walks, lanes, [&](std::size_t w) { return Walk(kernel, tables, i, stream(seed, StreamDomain::gather_walk, i, w)); },
          [](Walk& walk, std::size_t, PatchIndex j) { walk.advance(j); },
          [&](std::size_t w, const Walk& walk) { X[w] = walk.score(); }, counters);
    }
  });
  return X;
}

// Every walk and particle scores exactly the same driven alone or in lockstep batches of 16.
template <class K>
void check_lockstep_matches_single(const K& kernel, const RadiosityProblem& p, const std::string& name) {
  const std::uint64_t seed = 11;
  const std::size_t walks = 300;  // not a multiple of 16: partial batches
  for (const WalkMethod method : all_walk_methods()) {
    if (!is_gathering(method)) continue;
    for (std::size_t i = 0; i < kernel.size(); ++i) {
      WalkCounters batched_counters, single_counters;
      const std::vector<Rgb> batched =
          lockstep_gather_scores(method, kernel, i, walks, seed, kMaxLanes, batched_counters);
      const std::vector<Rgb> single = lockstep_gather_scores(method, kernel, i, walks, seed, 1, single_counters);
      // Each walk alone, one destination sample at a time (run_walk).
      const auto alone = test::gather_scores(method, kernel, i, static_cast<long>(walks), seed);
      int mismatches = 0;
      for (std::size_t w = 0; w < walks; ++w) {
        const Rgb x(alone[0][w], alone[1][w], alone[2][w]);
        mismatches += !(x == batched[w]).all() || !(x == single[w]).all();
      }
      INFO(name << ", " << method_name(method) << ", patch " << i);
      CHECK(mismatches == 0);
      CHECK(batched_counters.steps == single_counters.steps);
      CHECK(batched_counters.escapes == single_counters.escapes);
    }
  }
  // Shooting: each particle's list of (patch, power) scores.
  const ShootSource source = make_shoot_source(p.E, p.area);
  const ShootCollision::Tables tables(kernel.tables());
  using Particle = ShootCollision::Particle<K>;
  using Scores = std::vector<std::pair<std::size_t, Rgb>>;
  auto particle_scores = [&](std::size_t lanes) {
    std::vector<Scores> scores(walks);
    WalkCounters counters;
    run_lockstep(
        kernel, walks, lanes,
        [&](std::size_t w) { return Particle(kernel, tables, source, stream(seed, StreamDomain::shoot_particle, 0, w)); },
        [&](Particle& particle, std::size_t w, PatchIndex j) {
          particle.advance(j, [&](std::size_t jj, const Rgb& power) { scores[w].push_back({jj, power}); });
        },
        [](std::size_t, const Particle&) {}, counters);
    return scores;
  };
  const std::vector<Scores> batched = particle_scores(kMaxLanes), single = particle_scores(1);
  int mismatches = 0;
  for (std::size_t w = 0; w < walks; ++w) {
    mismatches += batched[w].size() != single[w].size();
    for (std::size_t s = 0; s < std::min(batched[w].size(), single[w].size()); ++s)
      mismatches += batched[w][s].first != single[w][s].first || !(batched[w][s].second == single[w][s].second).all();
  }
  INFO(name << ", shoot-collision");
  CHECK(mismatches == 0);
}

}  // namespace

TEST_CASE("walks in lockstep batches score exactly as walks run one at a time", "[walk][ray][lockstep]") {
  const std::vector<int> open = {0, 1, 2, 3, 4};  // escapes too
  const RadiosityProblem p = test::mixed_cube(open);
  const PatchSet patches = test::cube_patches(p, open);
  const std::vector<double> survival = survival_probabilities(p.rho, {});
  const BruteForceVisibility brute(patches);
  check_lockstep_matches_single(RayKernel(p, patches, brute, survival), p, "ray kernel, brute-force visibility");
  // Embree traces a batch as one packet of 16 and a lone ray as a packet of one.
  const EmbreeVisibility embree(patches);
  check_lockstep_matches_single(RayKernel(p, patches, embree, survival), p, "ray kernel, Embree");
  check_lockstep_matches_single(MatrixKernel(p, survival), p, "matrix kernel");
}

TEST_CASE("the ray kernel's rays are spawn_ray's for the same uniforms, to single precision", "[walk][ray]") {
  // A tilted planar quad and a triangle about 2000 away from the origin (extent about 1), where the float
  // rounding of the origin is largest against the offset eps = 8 FLT_EPSILON max|coordinate| (ray_offset.h).
  // Reference: sample_patch_point, sample_cosine_hemisphere and spawn_ray in double from the same four draws.
  // The origin's float error is a few roundings at the size of the coordinates (ray_kernel.h): at most
  // 2 FLT_EPSILON max|x|.
  PatchBuilder b;
  const int white = b.add_material("white", Rgb(0.5, 0.5, 0.5));
  const Vec3 o(1000, -2000, 500);
  // A planar convex quad in z = 0.1 x + 0.05 y (relative to o).
  b.add_quad(o, o + Vec3(1, 0, 0.1), o + Vec3(1.2, 1, 0.17), o + Vec3(0, 0.8, 0.04), white);
  b.add_triangle(o + Vec3(0, 0, 1), o + Vec3(1, 0, 1.5), o + Vec3(0, 1, 1.2), white);
  const PatchSet patches = b.build();
  const BruteForceVisibility visibility(patches);
  const RayKernel kernel(make_problem(patches, SparseF(2, 2)), patches, visibility, {0.5, 0.5});
  const double eps = ray_epsilon(patches);
  double scale = 0;  // max |coordinate|
  for (const Vec3& p : patches.points) scale = std::max(scale, p.cwiseAbs().maxCoeff());
  double origin_error = 0, direction_error = 0, lowest = INFINITY;
  for (std::size_t k = 0; k < patches.size(); ++k)
    for (std::uint64_t n = 0; n < 20000; ++n) {
      Rng rng = stream(5, StreamDomain::test, k, n), copy = rng;
      const Ray ray = kernel.sample_ray(k, rng);
      auto u = [&] { return static_cast<double>(copy.next_u32() >> 8) * 0x1.0p-24; };
      const double u1 = u(), u2 = u(), u3 = u(), u4 = u();
      const Vec3 x = sample_patch_point(patches, k, u1, u2);
      const Vec3 w = Frame(patches.normal[k]).to_world(sample_cosine_hemisphere(u3, u4));
      const Ray ref = spawn_ray(patches, k, x, w, eps);
      origin_error = std::max(origin_error, (ray.origin - ref.origin).cwiseAbs().maxCoeff());
      direction_error = std::max(direction_error, (ray.direction - ref.direction).cwiseAbs().maxCoeff());
      lowest = std::min(lowest, (ray.origin - x).dot(patches.normal[k]));  // height above the patch plane
    }
  INFO("eps " << eps << ", origin error " << origin_error << ", direction error " << direction_error
              << ", lowest origin above its plane " << lowest);
  CHECK(origin_error <= 2 * FLT_EPSILON * scale);
  CHECK(direction_error < 0x1.0p-20);  // a few float roundings of terms of size 1
  CHECK(lowest > 0.5 * eps);           // eps above the plane, less the origin error (at most eps / 4)
}

TEST_CASE("unit_circle turned by its quarter turns is within 2.5e-7 of (cos, sin) of 2 pi u", "[walk][ray]") {
  // Single precision: the bound is 4 float ulps of 1 (2^-22), over the grid of u the kernel draws from.
  double worst = 0;
  for (int k = 0; k <= 100000; k += int(kPacketSize)) {
    LaneFloats u;
    for (std::size_t l = 0; l < kPacketSize; ++l)
      u[l] = std::min(float(k + int(l)) / 100000.0f, 0x1.fffffep-1f);
    const QuarterTurns phi = unit_circle(u);
    for (std::size_t l = 0; l < kPacketSize; ++l) {
      double c = phi.cos_theta[l], s = phi.sin_theta[l];
      for (int q = 0; q < phi.q[l]; ++q) c = -std::exchange(s, c);  // (c, s) -> (-s, c)
      const double angle = 2 * kPi * double(u[l]);
      worst = std::max({worst, std::abs(c - std::cos(angle)), std::abs(s - std::sin(angle))});
    }
  }
  INFO("largest error " << worst);
  CHECK(worst < 0x1.0p-22);
}

TEST_CASE("gathering tasks spanning patches give each patch the moments of its own walks", "[walk][ray][lockstep]") {
  // With 5 walks per patch, one task of the solver holds the walks of all six patches in its lockstep lanes
  // (random_walk_solver.cpp, gather_layout): each patch's B and var must still be those of its walks (seed,
  // gather_walk, i, w), w = 0..4, replayed one at a time; the summation orders differ (shifted sums against two
  // passes), hence the relative tolerance of a few roundings.
  const std::vector<int> open = {0, 1, 2, 3, 4};  // escapes too
  const RadiosityProblem p = test::mixed_cube(open);
  const PatchSet patches = test::cube_patches(p, open);
  const EmbreeVisibility embree(patches);
  WalkOptions o;
  o.method = WalkMethod::gather_collision;
  o.kernel = WalkKernel::ray;
  o.walks_per_patch = 5;
  o.seed = 23;
  const Solution s = solve_random_walk(p, &patches, &embree, o);
  const RayKernel kernel(p, patches, embree, survival_probabilities(p.rho, {}));
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const auto x = test::gather_scores(o.method, kernel, i, o.walks_per_patch, o.seed);
    for (int c = 0; c < 3; ++c) {
      const SampleMoments m = sample_moments(x[c]);
      INFO("patch " << i << ", channel " << c);
      CHECK(s.B(static_cast<Eigen::Index>(i), c) == Approx(m.mean).epsilon(1e-12).margin(1e-300));
      CHECK(s.var(static_cast<Eigen::Index>(i), c) == Approx(m.var).epsilon(1e-9).margin(1e-12));
    }
  }
}
