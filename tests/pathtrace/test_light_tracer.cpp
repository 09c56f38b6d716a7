// Light tracing on patches: furnace and energy balance (exact), agreement with the MIS path tracer.
#include <catch2/catch.hpp>

#include "core/parallel.h"
#include "pathtrace/light_tracer.h"
#include "pathtrace/patch_average.h"
#include "scenes.h"
#include "support/stat_checks.h"
#include "visibility/brute_force_visibility.h"

using namespace radwalk;

namespace {
LightTraceOptions lt_options(long particles, std::uint64_t seed) {
  LightTraceOptions o;
  o.particles = particles;
  o.seed = seed;
  o.progress = false;
  return o;
}
}  // namespace

TEST_CASE("light tracer: furnace B = E / (1 - rho) on every patch", "[lighttrace][statistical]") {
  // H0 for 24 patches x 3 channels; alpha = 1e-3 family-wise.
  const Rgb rho(0.3, 0.5, 0.7), Le(1.0, 2.0, 0.5);
  const PatchSet p = test::furnace(rho, Le);
  const BruteForceVisibility vis(p);
  const Solution s = light_trace_patches(p, vis, lt_options(200000, 201));
  CHECK(s.method == "lighttrace");
  const double z = z_critical(sidak(1e-3, p.size() * 3));
  test::ZTable table("light-traced furnace B", z);
  for (std::size_t i = 0; i < p.size(); ++i)
    for (int c = 0; c < 3; ++c)
      table.add_patch(i, c, "patch " + std::to_string(i) + " channel " + std::to_string(c), s.B(i, c), s.B_se(i, c),
                      kPi * Le[c] / (1 - rho[c]));
  table.check(&p);
}

TEST_CASE("light tracer agrees with the MIS path tracer and conserves energy", "[lighttrace][statistical]") {
  // Scene: closed room, coloured walls, a reflecting emitter, an obstacle. H0: equal expectations per patch and
  // channel (two-sample z) and, for the uniform-rho variant, the exact area-weighted mean. alpha = 1e-3 for each
  // family (Sidak over its checks).
  PatchBuilder b;
  const int red = b.add_material("red", Rgb(0.63, 0.065, 0.05));
  const int white = b.add_material("white", Rgb(0.725, 0.71, 0.68));
  const int lamp = b.add_material("lamp", Rgb::Constant(0.78), Rgb(17, 12, 4));
  test::add_cube_outward(b, Vec3(0.3, 0.0001, 0.4), 0.35, white);
  const PatchSet p = test::closed_box(Vec3(1, 1, 1), 3, b, [&](int f, int a, int c) {
    if (f == 3 && a == 1 && c == 1) return lamp;
    return f == 1 ? red : white;
  });
  const BruteForceVisibility vis(p);
  const Solution lt = light_trace_patches(p, vis, lt_options(300000, 202));
  PatchAverageOptions po;
  po.spp = 1500;
  po.seed = 203;
  po.progress = false;
  const Solution pt = estimate_patch_averages(p, vis, po);
  const double z = z_critical(sidak(1e-3, p.size() * 3));
  test::check_solutions_agree(lt, pt, z, &p);

  // Energy balance with uniform rho.
  const Rgb rho(0.6, 0.5, 0.4);
  const PatchSet q = test::lit_box(rho, Rgb(5, 4, 3));
  const BruteForceVisibility vq(q);
  const Solution e = light_trace_patches(q, vq, lt_options(200000, 204));
  const Rgb emitted = test::emitted_power(q);
  const double z3 = z_critical(sidak(1e-3, 3));
  for (int c = 0; c < 3; ++c) {
    // Patches share particles (correlated scores), so the se of the weighted sum is bounded by the sum of the
    // weighted se's (sd(sum a_i X_i) <= sum a_i sd(X_i)): a conservative z-test.
    double mean = 0;
    for (std::size_t i = 0; i < q.size(); ++i) mean += q.area[i] * e.B(i, c);
    mean /= q.total_area();
    const double exact = emitted[c] / (q.total_area() * (1 - rho[c]));
    double se = 0;
    for (std::size_t i = 0; i < q.size(); ++i) se += q.area[i] * e.B_se(i, c);
    se /= q.total_area();
    test::check_z("light-traced area-weighted mean", mean, se, exact, z3);
  }
}

TEST_CASE("light tracer is bit-identical for 1 and 2 threads", "[lighttrace]") {
  PatchBuilder b;
  const int wall = b.add_material("wall", Rgb::Constant(0.5));
  const int lamp = b.add_material("lamp", Rgb::Constant(0.5), Rgb::Constant(2.0));
  const PatchSet p = test::closed_box(Vec3(1, 1, 1), 2, b, [&](int f, int, int) { return f == 3 ? lamp : wall; });
  const BruteForceVisibility vis(p);
  Solution one, two;
  {
    const ThreadLimit limit(1);
    one = light_trace_patches(p, vis, lt_options(50000, 205));
  }
  {
    const ThreadLimit limit(2);
    two = light_trace_patches(p, vis, lt_options(50000, 205));
  }
  CHECK((one.B == two.B).all());
  CHECK(one.steps == two.steps);
}
