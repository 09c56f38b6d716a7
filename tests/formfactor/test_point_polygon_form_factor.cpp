// The point-to-polygon form factor (formfactor/point_polygon_form_factor.h), its occlusion-corrected patch form
// factor (visible_form_factor.h) and the emitter columns of F (emitter_form_factors.h):
//   - the closed form against Howell's B-3 (differential element to a parallel rectangle, normal through a
//     corner) to 1e-12, and the unit cube's closure (a floor point sees the five other faces with sum 1);
//   - integrated over a receiving rectangle by Gauss-Legendre quadrature against the parallel (C-11) and
//     perpendicular (C-14) rectangles (quadrature accuracy 1e-8 relative, graded towards the shared edge);
//   - against brute-force Monte Carlo (2^20 uniform points on the polygon) on tilted and clipped configurations
//     (z-tests, family-wise alpha = 1e-3, Sidak);
//   - VisibleFormFactor unbiased: unoccluded (C-11, C-14, where the point-to-point estimator's variance is
//     infinite) and with an occluder (against an independent point-to-point estimate), t-tests over K = 40
//     shifts, family-wise alpha = 1e-3 (Sidak); zero variance where every point sees the whole target;
//   - estimate_emitter_form_factors: the emitter columns unbiased against the cube's exact F, the other columns
//     those of estimate_form_factors, bit-identical on 1 and 2 threads.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "core/parallel.h"
#include "core/rng.h"
#include "formfactor/emitter_form_factors.h"
#include "formfactor/point_polygon_form_factor.h"
#include "formfactor/visible_form_factor.h"
#include "patch/patch_builder.h"
#include "support/reference_problems.h"
#include "support/stat_checks.h"
#include "support/view_factors.h"
#include "visibility/brute_force_visibility.h"

using namespace radwalk;

namespace {

// The two-sided critical value of Student's t with nu degrees of freedom at the level of the normal critical value
// z (Cornish-Fisher expansion, within 1e-3 of the exact quantile for nu >= 20 at z <= 5; as test_sobol_sampler.cpp).
double t_critical(double z, double nu) {
  const double z2 = z * z;
  return z + (z2 * z + z) / (4 * nu) + (5 * z2 * z2 * z + 16 * z2 * z + 3 * z) / (96 * nu * nu) +
         (3 * z2 * z2 * z2 * z + 19 * z2 * z2 * z + 17 * z2 * z - 15 * z) / (384 * nu * nu * nu);
}

// Howell B-3: element at the origin, normal +z, rectangle [0, a] x [0, b] at height c facing down.
double b3(double a, double b, double c) {
  const double A = a / c, B = b / c;
  return (A / std::sqrt(1 + A * A) * std::atan(B / std::sqrt(1 + A * A)) +
          B / std::sqrt(1 + B * B) * std::atan(A / std::sqrt(1 + B * B))) /
         (2 * kPi);
}

// A rectangle's corners counter-clockwise about `normal`: o, o + u, o + u + v, o + v (u x v along normal).
std::vector<Vec3> rect(const Vec3& o, const Vec3& u, const Vec3& v) { return {o, o + u, o + u + v, o + v}; }

double ff(const Vec3& x, const Vec3& n, const std::vector<Vec3>& P) {
  const Vec3 np = (P[1] - P[0]).cross(P[2] - P[0]).normalized();
  return point_polygon_form_factor(x, n, P.data(), int(P.size()), np);
}

// Composite Gauss-Legendre on [0, 1] with pieces graded geometrically towards 0 (ratio 1/2, `levels` of them)
// and `order` points per piece.
void graded_rule(int levels, int order, std::vector<double>& x, std::vector<double>& w) {
  std::vector<double> gx, gw;
  test::gauss_legendre(order, gx, gw);
  x.clear();
  w.clear();
  double hi = 1;
  for (int l = 0; l <= levels; ++l) {
    const double lo = l == levels ? 0 : hi / 2;
    for (int k = 0; k < order; ++k) {
      x.push_back(lo + (hi - lo) * gx[k]);
      w.push_back((hi - lo) * gw[k]);
    }
    hi = lo;
  }
}

}  // namespace

TEST_CASE("the point-to-polygon form factor matches Howell B-3 and the cube's closure", "[formfactor][analytic]") {
  for (const auto& [a, b, c] : std::vector<std::array<double, 3>>{{1, 1, 1}, {2, 0.5, 1}, {0.3, 3, 0.7}}) {
    // Corners counter-clockwise about -z (facing the element below).
    const std::vector<Vec3> P = rect(Vec3(0, 0, c), Vec3(0, b, 0), Vec3(a, 0, 0));
    INFO("a " << a << " b " << b << " c " << c);
    CHECK(std::abs(ff(Vec3::Zero(), Vec3::UnitZ(), P) - b3(a, b, c)) <= 1e-12);
  }
  CHECK(std::abs(b3(1, 1, 1) - 0.1385316) < 1e-7);
  // Facing away (the back of P towards the element): nothing.
  CHECK(ff(Vec3::Zero(), Vec3::UnitZ(), rect(Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0, 1, 0))) == 0);
  // A point on the floor of the unit cube sees the five other faces (inward normals), in total 1; the walls touch
  // the floor's plane, so they are clipped at their bottom edge.
  const std::vector<std::vector<Vec3>> faces = {
      rect(Vec3(0, 0, 1), Vec3(0, 1, 0), Vec3(1, 0, 0)),   // ceiling, normal -z
      rect(Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)),   // x = 0, normal +x
      rect(Vec3(1, 0, 0), Vec3(0, 0, 1), Vec3(0, 1, 0)),   // x = 1, normal -x
      rect(Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(1, 0, 0)),   // y = 0, normal +y
      rect(Vec3(0, 1, 0), Vec3(1, 0, 0), Vec3(0, 0, 1))};  // y = 1, normal -y
  for (const Vec3& x : {Vec3(0.5, 0.5, 0), Vec3(0.1, 0.8, 0), Vec3(0.999, 0.001, 0)}) {
    double sum = 0;
    for (const auto& f : faces) sum += ff(x, Vec3::UnitZ(), f);
    INFO("x " << x.transpose());
    CHECK(std::abs(sum - 1) <= 1e-12);
  }
}

TEST_CASE("a point in the polygon's own plane sees it edge-on whatever the rounding", "[formfactor][analytic]") {
  // An emitter split into patches: a point of one patch, or of its coplanar neighbour, lies in the plane up to
  // rounding (n_P . (x - p_0) of order 1e-17, of either sign); Lambert's sum, whose terms are then all +-gamma_k,
  // gives 1 inside the outline. The factor is 0 there, and tends to its closed form continuously above the plane.
  const Vec3 down(0, -1, 0);
  const std::vector<Vec3> P = rect(Vec3(2.75, 2.8, 1.5), Vec3(0.25, 0, 0), Vec3(0, 0, 0.25));  // facing -y
  REQUIRE((P[1] - P[0]).cross(P[2] - P[0]).normalized().dot(down) == Approx(1));
  int inside = 0;
  for (int a = 1; a < 40; ++a)
    for (int b = 1; b < 40; ++b) {
      // Points of P by bilinear interpolation (rounded as a point sampler's are), and of a neighbour beside it.
      const double u = a / 40.0, v = b / 40.0;
      const Vec3 x = (1 - u) * ((1 - v) * P[0] + v * P[1]) + u * ((1 - v) * P[3] + v * P[2]);
      inside += ff(x, down, P) != 0;
      CHECK(ff(x + Vec3(0.25, 0, 0), down, P) == 0);
      CHECK(ff(x, -down, P) == 0);
    }
  CHECK(inside == 0);
  // Just in front (facing it, 1e-6 of its size below its centre): B-3 with four quarter rectangles, nearly 1.
  const Vec3 centre = 0.5 * (P[0] + P[2]);
  CHECK(ff(centre + Vec3(0, -0.25e-6, 0), Vec3(0, 1, 0), P) == Approx(4 * b3(0.125, 0.125, 0.25e-6)).epsilon(1e-9));
}

TEST_CASE("the point-to-polygon form factor integrates to the rectangle view factors C-11 and C-14",
          "[formfactor][analytic]") {
  std::vector<double> gx, gw;
  graded_rule(30, 12, gx, gw);
  // C-11: unit squares at distance c (receiver z = 0, normal +z).
  for (const double c : {0.5, 1.0, 2.0}) {
    const std::vector<Vec3> P = rect(Vec3(0, 0, c), Vec3(0, 1, 0), Vec3(1, 0, 0));
    std::vector<double> ux, uw;
    test::gauss_legendre(24, ux, uw);
    double F = 0;
    for (std::size_t i = 0; i < ux.size(); ++i)
      for (std::size_t j = 0; j < ux.size(); ++j) F += uw[i] * uw[j] * ff(Vec3(ux[i], ux[j], 0), Vec3::UnitZ(), P);
    INFO("c " << c);
    CHECK(std::abs(F - test::parallel_rectangles(1, 1, c)) <= 1e-8 * test::parallel_rectangles(1, 1, c));
  }
  // C-14: the receiver (z = 0, x in [0, w], y in [0, l]) and a wall x = 0 of height h facing +x, sharing the
  // edge x = 0 of length l; x graded towards the edge.
  for (const auto& [l, w, h] : std::vector<std::array<double, 3>>{{1, 1, 1}, {1, 2, 0.5}}) {
    const std::vector<Vec3> P = rect(Vec3(0, 0, 0), Vec3(0, l, 0), Vec3(0, 0, h));
    // y graded towards both ends of the shared edge (the corners where F(x -> wall) is least smooth).
    std::vector<double> uy, wy;
    for (std::size_t k = 0; k < gx.size(); ++k) {
      uy.push_back(0.5 * gx[k]);
      wy.push_back(0.5 * gw[k]);
      uy.push_back(1 - 0.5 * gx[k]);
      wy.push_back(0.5 * gw[k]);
    }
    double F = 0;
    for (std::size_t i = 0; i < gx.size(); ++i)
      for (std::size_t j = 0; j < uy.size(); ++j)
        F += gw[i] * wy[j] * ff(Vec3(w * gx[i], l * uy[j], 0), Vec3::UnitZ(), P);
    const double exact = test::perpendicular_rectangles(l, w, h);
    INFO("l " << l << " w " << w << " h " << h);
    CHECK(std::abs(F - exact) <= 1e-8 * exact);
  }
}

TEST_CASE("the point-to-polygon form factor agrees with brute-force Monte Carlo on tilted and clipped polygons",
          "[formfactor][analytic]") {
  struct Case {
    Vec3 x, n;
    std::vector<Vec3> P;
  };
  const Vec3 tilt = Vec3(0.3, -0.2, 1).normalized();
  const std::vector<Case> cases = {
      {Vec3::Zero(), tilt, {Vec3(-0.5, -0.4, 1.2), Vec3(-0.5, 0.9, 1.0), Vec3(0.8, 0.9, 1.3), Vec3(0.8, -0.4, 1.5)}},
      // Straddling the receiver's plane (clipped): a wall standing across the plane z = 0, facing -x.
      {Vec3::Zero(), Vec3::UnitZ(), rect(Vec3(1, -1, -0.5), Vec3(0, 2, 0), Vec3(0, 0, 1.5))},
      // A triangle, tilted receiver, partly below its plane.
      {Vec3(0.1, 0.2, 0), tilt, {Vec3(-1, 0.5, 0.4), Vec3(1, 0.5, -0.3), Vec3(0.2, 0.6, 1.5)}}};
  const double z_crit = z_critical(sidak(1e-3, cases.size()));
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Case& c = cases[k];
    // Corners counter-clockwise about the normal that faces x.
    std::vector<Vec3> P = c.P;
    Vec3 np = (P[1] - P[0]).cross(P[2] - P[0]).normalized();
    if (np.dot(c.x - P[0]) < 0) {
      std::reverse(P.begin(), P.end());
      np = -np;
    }
    const double exact = ff(c.x, c.n, P);
    REQUIRE(exact > 0);
    // Uniform points on the polygon (fan of triangles from corner 0, chosen by area).
    std::vector<double> tri_area;
    double area = 0;
    for (std::size_t t = 1; t + 1 < P.size(); ++t) {
      tri_area.push_back(0.5 * (P[t] - P[0]).cross(P[t + 1] - P[0]).norm());
      area += tri_area.back();
    }
    Rng rng = stream(3, StreamDomain::test, k, 0);
    constexpr long kSamples = 1 << 20;
    double sum = 0, sum2 = 0;
    for (long s = 0; s < kSamples; ++s) {
      double u = rng.uniform() * area;
      std::size_t t = 0;
      while (t + 1 < tri_area.size() && u >= tri_area[t]) u -= tri_area[t++];
      double a = rng.uniform(), b = rng.uniform();
      if (a + b > 1) {
        a = 1 - a;
        b = 1 - b;
      }
      const Vec3 y = P[0] + a * (P[t + 1] - P[0]) + b * (P[t + 2] - P[0]);
      const Vec3 d = y - c.x;
      const double r2 = d.squaredNorm(), cx = c.n.dot(d), cy = -np.dot(d);
      const double g = cx > 0 && cy > 0 ? area * cx * cy / (kPi * r2 * r2) : 0.0;
      sum += g;
      sum2 += g * g;
    }
    const double mean = sum / kSamples, se = std::sqrt((sum2 / kSamples - mean * mean) / (kSamples - 1));
    test::check_z("case " + std::to_string(k) + ": Monte Carlo against Lambert", mean, se, exact, z_crit);
  }
}

namespace {

// Two unit squares facing each other at distance c (receiver 0 at z = 0 facing up, target 1 facing down), with
// an optional occluding square (both sides opaque: one-sided, facing down, then its back faces the receiver).
PatchSet squares(double c, bool occluder) {
  PatchBuilder b;
  const int grey = b.add_material("grey", Rgb(0.5, 0.5, 0.5));
  const int light = b.add_material("light", Rgb(0, 0, 0), Rgb(1, 1, 1));
  b.add_quad(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), grey);
  b.add_quad(Vec3(0, 0, c), Vec3(0, 1, c), Vec3(1, 1, c), Vec3(1, 0, c), light);
  if (occluder)
    b.add_quad(Vec3(0.3, 0.2, c / 2), Vec3(0.3, 0.7, c / 2), Vec3(0.6, 0.7, c / 2), Vec3(0.6, 0.2, c / 2), grey);
  return b.build();
}

// A floor and a wall sharing an edge (C-14 with l = w = h = 1): patch 0 the floor, patch 1 the wall x = 0.
PatchSet floor_and_wall() {
  PatchBuilder b;
  const int grey = b.add_material("grey", Rgb(0.5, 0.5, 0.5));
  const int light = b.add_material("light", Rgb(0, 0, 0), Rgb(1, 1, 1));
  b.add_quad(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), grey);
  b.add_quad(Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(0, 1, 1), Vec3(0, 0, 1), light);
  return b.build();
}

SobolShift shift_of(std::uint64_t k) {
  Rng rng = stream(11, StreamDomain::test, k, 1);
  SobolShift s;
  for (auto& w : s.word) w = rng.next_u32();
  return s;
}

}  // namespace

TEST_CASE("the visible form factor is unbiased, with and without occlusion, and exact where all is seen",
          "[formfactor][visible]") {
  constexpr int K = 40;
  constexpr long M = 64;
  const double t_crit = t_critical(z_critical(sidak(1e-3, 3)), K - 1);  // three cases
  struct Case {
    std::string what;
    PatchSet patches;
    double exact;  // NaN: against the point-to-point estimate
  };
  std::vector<Case> cases;
  cases.push_back({"C-11 squares at 0.5", squares(0.5, false), test::parallel_rectangles(1, 1, 0.5)});
  cases.push_back({"C-14 floor and wall", floor_and_wall(), test::perpendicular_rectangles(1, 1, 1)});
  cases.push_back({"squares at 0.5 with an occluder", squares(0.5, true), std::nan("")});
  for (const Case& c : cases) {
    const BruteForceVisibility vis(c.patches);
    const VisibleFormFactor visible(c.patches, vis);
    double sum = 0, sum2 = 0;
    long rays = 0;
    for (int k = 0; k < K; ++k) {
      const double f = visible.estimate(0, 1, M, shift_of(std::uint64_t(k)), rays);
      sum += f;
      sum2 += f * f;
    }
    const double mean = sum / K, se = std::sqrt(std::max(0.0, sum2 / K - mean * mean) / (K - 1));
    double expected = c.exact, se_ref = 0;
    if (std::isnan(expected)) {
      // Independent point-to-point estimate: A_e G V at uniform pairs (x, y), 2^18 of them.
      Rng rng = stream(12, StreamDomain::test, 0, 0);
      double s = 0, s2 = 0;
      constexpr long n = 1 << 18;
      for (long q = 0; q < n; ++q) {
        const Vec3 x = sample_patch_point(c.patches, 0, rng.uniform(), rng.uniform());
        const Vec3 y = sample_patch_point(c.patches, 1, rng.uniform(), rng.uniform());
        const Vec3 d = y - x;
        const double r = d.norm();
        Ray ray{x, d / r, r * (1 - 1e-9)};
        const double g = vis.occluded(ray) ? 0.0 : d.z() * d.z() / (kPi * r * r * r * r);
        s += g;
        s2 += g * g;
      }
      expected = s / n;
      se_ref = std::sqrt((s2 / n - expected * expected) / (n - 1));
    }
    test::check_z(c.what, mean, std::hypot(se, se_ref), expected, t_crit);
    CHECK(rays > 0);
  }
  // Where every point of the receiver sees the whole target the estimate is the mean of the exact F(x -> e) over
  // the points: a tiny receiver at the centre below a large square gets 4 B-3(100, 100, 1) from any shift.
  PatchBuilder b;
  const int grey = b.add_material("grey", Rgb(0.5, 0.5, 0.5));
  const int light = b.add_material("light", Rgb(0, 0, 0), Rgb(1, 1, 1));
  constexpr double h = 5e-4, L = 100;
  b.add_quad(Vec3(-h, -h, 0), Vec3(h, -h, 0), Vec3(h, h, 0), Vec3(-h, h, 0), grey);
  b.add_quad(Vec3(-L, -L, 1), Vec3(-L, L, 1), Vec3(L, L, 1), Vec3(L, -L, 1), light);
  const PatchSet big = b.build();
  const BruteForceVisibility vis(big);
  long rays = 0;
  const VisibleFormFactor visible(big, vis);
  const double f1 = visible.estimate(0, 1, 16, shift_of(98), rays), f2 = visible.estimate(0, 1, 16, shift_of(99), rays);
  CHECK(std::abs(f1 - 4 * b3(L, L, 1)) < 1e-9);
  CHECK(std::abs(f1 - f2) < 1e-9);
}

TEST_CASE("emitter columns of F: unbiased against the cube's exact F, the rest from the cosine rays, any threads",
          "[formfactor][visible]") {
  // The unit cube of reference_problems.h with face 0 (x = 0) emitting: every row's column 0 is replaced.
  PatchBuilder b;
  const Vec3 center(0.5, 0.5, 0.5);
  for (int f = 0; f < 6; ++f) {
    const int m = b.add_material("face" + std::to_string(f), Rgb(0.5, 0.5, 0.5),
                                 f == 0 ? Rgb(1, 1, 1) : Rgb(0, 0, 0));
    const int axis = f / 2, u = (axis + 1) % 3, v = (axis + 2) % 3;
    std::vector<Vec3> q(4, Vec3::Zero());
    const double uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int c = 0; c < 4; ++c) {
      q[c](axis) = f % 2;
      q[c](u) = uv[c][0];
      q[c](v) = uv[c][1];
    }
    if ((q[1] - q[0]).cross(q[2] - q[0]).dot(center - q[0]) < 0) std::swap(q[1], q[3]);
    b.add_quad(q[0], q[1], q[2], q[3], m);
  }
  const PatchSet cube = b.build();
  const BruteForceVisibility vis(cube);
  constexpr int K = 30;
  FormFactorOptions o;
  o.rays_per_patch = 200;
  std::vector<double> sum(6, 0), sum2(6, 0);
  for (int k = 0; k < K; ++k) {
    o.seed = std::uint64_t(k + 1);
    const EmitterFormFactors ef = estimate_emitter_form_factors(cube, vis, o, 32);
    CHECK(ef.emitter_columns == 1);
    const FormFactors plain = estimate_form_factors(cube, vis, o);
    for (int i = 0; i < 6; ++i) {
      const double f = ef.form_factors.F.coeff(i, 0);
      sum[std::size_t(i)] += f;
      sum2[std::size_t(i)] += f * f;
      for (int j = 1; j < 6; ++j) CHECK(ef.form_factors.F.coeff(i, j) == plain.F.coeff(i, j));
    }
  }
  test::ZTable table("emitter column of the cube, 32 samples per row", t_critical(z_critical(sidak(1e-3, 5)), K - 1));
  for (int i = 1; i < 6; ++i) {
    const double mean = sum[std::size_t(i)] / K;
    const double se = std::sqrt(std::max(0.0, sum2[std::size_t(i)] / K - mean * mean) / (K - 1));
    table.add("F_" + std::to_string(i) + "0", mean, se, (i == 1) ? test::kOpposite : test::kAdjacent);
  }
  table.check();
  // Threads.
  o.seed = 5;
  EmitterFormFactors one, two;
  {
    ThreadLimit limit(1);
    one = estimate_emitter_form_factors(cube, vis, o, 32);
  }
  {
    ThreadLimit limit(2);
    two = estimate_emitter_form_factors(cube, vis, o, 32);
  }
  CHECK(one.shadow_rays == two.shadow_rays);
  CHECK((Eigen::MatrixXf(one.form_factors.F) == Eigen::MatrixXf(two.form_factors.F)));
  CHECK_THROWS(estimate_emitter_form_factors(cube, vis, o, 0));
}
