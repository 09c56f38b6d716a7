// The exact test of the path tracer on curved surfaces: inside a sphere with uniform reflectance and an emitting
// cap, every wall point receives the same irradiance (analytic_sphere.h), so every estimate of the radiosity at a
// point, of the radiance seen from inside and of a patch average has one known value. No discretisation error.
#include <catch2/catch.hpp>
#include <vector>

#include "analytic_sphere.h"
#include "core/moments.h"
#include "direction_bins.h"
#include "pathtrace/light_tracer.h"
#include "pathtrace/patch_average.h"
#include "scenes.h"
#include "support/stat_checks.h"

using namespace radwalk;

namespace {
const IntegratorKind kAll[] = {IntegratorKind::implicit, IntegratorKind::nee, IntegratorKind::mis};

// The scene of every test below: off-centre sphere, 8 x 16 patches, the top two bands emit.
const test::SphereCells kCells{Vec3(0.3, -0.2, 0.5), 1.7, 8, 16};
const Rgb kRho(0.3, 0.5, 0.7), kE(1.0, 2.0, 0.5);
constexpr int kEmittingBands = 2;

// Irradiance at every wall point: Phi_e / ((1 - rho) A), A = 4 pi R^2.
Rgb exact_irradiance(const PatchSet& p) {
  const double A = 4 * kPi * kCells.radius * kCells.radius;
  return test::emitted_power(p) / ((1 - kRho) * A);
}
}  // namespace

TEST_CASE("analytic sphere test scene: areas, sampling and intersection agree", "[pathtrace][sphere]") {
  const auto scene = test::make_sphere_scene(kCells, kRho, kE, kEmittingBands);
  const PatchSet& p = scene->patches;
  REQUIRE(p.size() == 128);
  CHECK(p.total_area() == Approx(4 * kPi * kCells.radius * kCells.radius).epsilon(1e-12));
  Rng rng = stream(7, StreamDomain::test, 0);
  for (int k = 0; k < 2000; ++k) {
    const auto i = static_cast<PatchIndex>(k % p.size());
    // Points sampled on patch i lie on the sphere and in patch i.
    const Vec3 x = scene->geometry.sample_point(i, 0.01 + 0.98 * rng.uniform(), 0.01 + 0.98 * rng.uniform());
    INFO("patch " << i << " point " << x.transpose());
    CHECK((x - kCells.centre).norm() == Approx(kCells.radius).epsilon(1e-12));
    CHECK(kCells.locate(x) == i);
    // A ray leaving x inward hits the sphere at the other end of its chord, length 2 R cos(theta).
    const Vec3 n = scene->geometry.normal(i, x);
    const Vec3 d = (n + 0.9 * test::uniform_sphere(rng.uniform(), rng.uniform())).normalized();
    const Hit hit = scene->visibility.intersect(scene->geometry.spawn_ray(i, x, d));
    REQUIRE_FALSE(hit.missed());
    CHECK(hit.front);
    CHECK(hit.t == Approx(2 * kCells.radius * d.dot(n)).epsilon(1e-6));
  }
}

TEST_CASE("inside a sphere with an emissive cap every wall point has the same radiance", "[pathtrace][sphere]") {
  // H0: at each of 24 wall points (8 on the cap), B(x) = E(x) + rho E_irr exactly, for each integrator; and the
  // radiance seen from 16 interior points along random rays is B(y) / pi at the wall point y hit.
  // 3 integrators x (24 + 16) estimates x 3 channels; alpha = 1e-3 family-wise (Sidak).
  const auto scene = test::make_sphere_scene(kCells, kRho, kE, kEmittingBands);
  const PatchSet& p = scene->patches;
  const Rgb E_irr = exact_irradiance(p);
  const double z = z_critical(sidak(1e-3, 3 * (24 + 16) * 3));
  const long n = 20000;
  for (IntegratorKind kind : kAll) {
    IntegratorOptions io;
    io.kind = kind;
    const PathIntegrator integrator(p, scene->geometry, scene->visibility, io);
    PathCounters counters;
    Rng pick = stream(11, StreamDomain::test, 0);
    // Wall points: irradiance estimates at fixed points, 8 on the cap and 16 below it.
    for (int k = 0; k < 24; ++k) {
      const int band = k < 8 ? kCells.n_z - 1 - k % kEmittingBands : k % (kCells.n_z - kEmittingBands);
      const PatchIndex i = kCells.index(band, static_cast<int>(pick.uniform() * kCells.n_phi));
      const Vec3 x = scene->geometry.sample_point(i, pick.uniform(), pick.uniform());
      std::vector<PowerSums> m(3);
      for (long s = 0; s < n; ++s) {
        Rng rng = stream(12, StreamDomain::test, static_cast<std::uint64_t>(k), static_cast<std::uint64_t>(s));
        const Rgb y = p.E[i] + p.rho[i] * integrator.irradiance(i, x, rng, counters);
        for (int c = 0; c < 3; ++c) m[c].add(y[c]);
      }
      for (int c = 0; c < 3; ++c) {
        INFO(to_string(kind) << " wall point " << k << " on patch " << i << " channel " << c);
        test::check_z("B(x)", m[c].mean(), m[c].standard_error(), p.E[i][c] + kRho[c] * E_irr[c], z);
      }
    }
    // Radiance seen from inside: a random interior point, a random direction; L = B(y) / pi at the hit y.
    for (int k = 0; k < 16; ++k) {
      const Vec3 o = kCells.centre + 0.8 * kCells.radius * std::cbrt(pick.uniform()) *
                                         test::uniform_sphere(pick.uniform(), pick.uniform());
      Ray ray;
      ray.origin = o;
      ray.direction = test::uniform_sphere(pick.uniform(), pick.uniform());
      const PatchIndex j = scene->visibility.intersect(ray).patch;
      REQUIRE(j >= 0);
      std::vector<PowerSums> m(3);
      for (long s = 0; s < n; ++s) {
        Rng rng = stream(13, StreamDomain::test, static_cast<std::uint64_t>(k), static_cast<std::uint64_t>(s));
        const Rgb L = integrator.radiance(ray, rng, counters);
        for (int c = 0; c < 3; ++c) m[c].add(L[c]);
      }
      for (int c = 0; c < 3; ++c) {
        INFO(to_string(kind) << " interior ray " << k << " to patch " << j << " channel " << c);
        test::check_z("L", m[c].mean(), m[c].standard_error(), (p.E[j][c] + kRho[c] * E_irr[c]) * kInvPi, z);
      }
    }
  }
}

TEST_CASE("inside a sphere, path-traced and light-traced patch averages equal the exact radiosity",
          "[pathtrace][sphere]") {
  // H0: B_i = E_i + rho E_irr on all 128 patches x 3 channels, for 3 integrators and the light tracer;
  // alpha = 1e-3 family-wise (Sidak).
  const auto scene = test::make_sphere_scene(kCells, kRho, kE, kEmittingBands);
  const PatchSet& p = scene->patches;
  const Rgb E_irr = exact_irradiance(p);
  const double z = z_critical(sidak(1e-3, 4 * p.size() * 3));
  std::vector<Solution> solutions;
  for (IntegratorKind kind : kAll) {
    PatchAverageOptions o;
    o.spp = 4096;
    o.seed = 21;
    o.integrator.kind = kind;
    o.progress = false;
    solutions.push_back(estimate_patch_averages(p, scene->geometry, scene->visibility, o));
  }
  LightTraceOptions lo;
  lo.particles = 2000000;
  lo.seed = 22;
  lo.progress = false;
  solutions.push_back(light_trace_patches(p, scene->geometry, scene->visibility, lo));
  for (const Solution& s : solutions) {
    test::ZTable table("B_i, " + s.method, z);
    for (std::size_t i = 0; i < p.size(); ++i)
      for (int c = 0; c < 3; ++c)
        table.add_patch(i, c, "patch " + std::to_string(i) + " channel " + std::to_string(c), s.B(i, c),
                        s.B_se(i, c), p.E[i][c] + kRho[c] * E_irr[c]);
    table.check(&p);
  }
}
