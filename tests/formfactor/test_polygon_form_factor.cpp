// The exact polygon-to-polygon form factor by contour integration (formfactor/polygon_form_factor.h):
//   - parallel, directly opposed rectangles (Howell C-11) and perpendicular rectangles sharing an edge (C-14) to
//     1e-10 relative, at several aspect ratios, and rectangles on perpendicular walls meeting at a corner only;
//   - adjacent pairs: a rectangle cut in a grid of cells on each wall, the cells' exchange areas summed against
//     C-14 of the whole rectangles (pairs sharing an edge, a corner, or collinear edges);
//   - non-parallel edges (triangles, tilted polygons) against the Gauss-Legendre contour quadrature of the test
//     support (smooth there, 1e-12), and triangles sharing a corner against the sum over a fine split;
//   - coplanar polygons: F = 0; polygons behind each other: 0; reciprocity A_i F_ij = A_j F_ji bit for bit for
//     patches (patch_exchange_area), to rounding for polygons;
//   - far pairs (the far-field Gauss rule): parallel rectangles at 10 to 3000 sizes against their Taylor series to
//     1e-12 (1e-10 at 10 sizes, where the contour integral is used; the contour sum alone misses by more than 1e-9
//     at 3000 sizes, shown), and tilted quadrilaterals and triangles just beyond the switch against the contour sum to 1e-9.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <vector>

#include "formfactor/polygon_form_factor.h"
#include "patch/patch_builder.h"
#include "support/box_scenes.h"
#include "support/view_factors.h"

using namespace radwalk;

namespace {

// A_P F_PQ for polygons given as vectors (normals from the corner order).
double exchange_area(const std::vector<Vec3>& p, const std::vector<Vec3>& q) {
  const Vec3 np = (p[1] - p[0]).cross(p[2] - p[0]).normalized();
  const Vec3 nq = (q[1] - q[0]).cross(q[2] - q[0]).normalized();
  return polygon_exchange_area(p.data(), int(p.size()), np, q.data(), int(q.size()), nq);
}

double area_of(const std::vector<Vec3>& p) {
  Vec3 s = Vec3::Zero();
  for (std::size_t k = 1; k + 1 < p.size(); ++k) s += (p[k] - p[0]).cross(p[k + 1] - p[0]);
  return 0.5 * s.norm();
}

// Rectangle [x0, x1] x [y0, y1] in the plane z = h, facing +z (up) or -z.
std::vector<Vec3> floor_rect(double x0, double x1, double y0, double y1, double h, bool up) {
  std::vector<Vec3> r = {{x0, y0, h}, {x1, y0, h}, {x1, y1, h}, {x0, y1, h}};
  if (!up) std::swap(r[1], r[3]);
  return r;
}

// Rectangle [x0, x1] x [z0, z1] in the plane y = 0, facing +y.
std::vector<Vec3> wall_rect(double x0, double x1, double z0, double z1) {
  return {{x0, 0, z0}, {x0, 0, z1}, {x1, 0, z1}, {x1, 0, z0}};
}

}  // namespace

TEST_CASE("polygon form factor: parallel rectangles equal Howell C-11 to 1e-10", "[formfactor][polygon]") {
  for (const auto& abc : std::vector<std::array<double, 3>>{{1, 1, 1}, {2, 0.5, 1}, {0.1, 0.1, 1}, {3, 1, 0.2}, {1, 1, 1e-3}}) {
    const double a = abc[0], b = abc[1], c = abc[2];
    const auto lower = floor_rect(0, a, 0, b, 0, true), upper = floor_rect(0, a, 0, b, c, false);
    const double expected = test::parallel_rectangles(a, b, c);
    const double F = exchange_area(lower, upper) / (a * b);
    INFO("a " << a << " b " << b << " c " << c);
    CHECK(F == Approx(expected).epsilon(1e-10).margin(0));
    CHECK(exchange_area(upper, lower) / (a * b) == Approx(expected).epsilon(1e-10).margin(0));
  }
}

TEST_CASE("polygon form factor: perpendicular rectangles sharing an edge equal Howell C-14 to 1e-10",
          "[formfactor][polygon]") {
  for (const auto& lwh : std::vector<std::array<double, 3>>{{1, 1, 1}, {1, 0.2, 3}, {2, 1, 0.5}, {0.05, 1, 1}}) {
    const double l = lwh[0], w = lwh[1], h = lwh[2];
    const auto floor = floor_rect(0, l, 0, w, 0, true), wall = wall_rect(0, l, 0, h);
    const double expected = test::perpendicular_rectangles(l, w, h);
    INFO("l " << l << " w " << w << " h " << h);
    CHECK(exchange_area(floor, wall) / (l * w) == Approx(expected).epsilon(1e-10).margin(0));
    CHECK(exchange_area(wall, floor) / (l * h) == Approx(test::perpendicular_rectangles(l, h, w)).epsilon(1e-10).margin(0));
  }
}

TEST_CASE("polygon form factor: grids of cells on two perpendicular walls sum to C-14 (adjacent and corner pairs)",
          "[formfactor][polygon]") {
  // Floor [0, 1] x [0, 1] cut into n x n cells, wall [0, 1] x [0, 1] (x, z) likewise: cells that share an edge
  // (along the joint), a corner, collinear edges, or nothing. The sum of all n^4 exchange areas is C-14.
  const int n = 3;
  double sum = 0;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      for (int c = 0; c < n; ++c)
        for (int d = 0; d < n; ++d)
          sum += exchange_area(floor_rect(double(a) / n, double(a + 1) / n, double(b) / n, double(b + 1) / n, 0, true),
                          wall_rect(double(c) / n, double(c + 1) / n, double(d) / n, double(d + 1) / n));
  CHECK(sum == Approx(test::perpendicular_rectangles(1, 1, 1)).epsilon(1e-10).margin(0));
  // One adjacent pair against its own decomposition: the cell pair sharing the edge [0, 1/3] on the joint is C-14.
  CHECK(exchange_area(floor_rect(0, 1.0 / 3, 0, 1.0 / 3, 0, true), wall_rect(0, 1.0 / 3, 0, 1.0 / 3)) / (1.0 / 9) ==
        Approx(test::perpendicular_rectangles(1.0 / 3, 1.0 / 3, 1.0 / 3)).epsilon(1e-10).margin(0));
}

TEST_CASE("polygon form factor: parallel cells of two opposite walls sum to C-11", "[formfactor][polygon]") {
  const int n = 4;
  double sum = 0;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      for (int c = 0; c < n; ++c)
        for (int d = 0; d < n; ++d)
          sum += exchange_area(floor_rect(double(a) / n, double(a + 1) / n, double(b) / n, double(b + 1) / n, 0, true),
                          floor_rect(double(c) / n, double(c + 1) / n, double(d) / n, double(d + 1) / n, 1, false));
  CHECK(sum == Approx(test::parallel_rectangles(1, 1, 1)).epsilon(1e-10).margin(0));
}

TEST_CASE("polygon form factor: non-parallel edges against the contour quadrature", "[formfactor][polygon]") {
  // Separated polygons (smooth integrands, quadrature accurate to ~1e-12): a triangle facing a tilted quad.
  const std::vector<Vec3> tri = {{0, 0, 0}, {1, 0.2, 0}, {0.3, 0.9, 0}};
  const std::vector<Vec3> quad = {{0.1, 0.2, 1.0}, {-0.2, 1.1, 1.3}, {0.9, 1.0, 1.2}, {1.0, 0.1, 0.9}};
  const double reference = test::polygon_exchange_area(tri, quad, 4, 20);
  CHECK(exchange_area(tri, quad) == Approx(reference).epsilon(1e-10).margin(0));
  CHECK(exchange_area(quad, tri) == Approx(reference).epsilon(1e-10).margin(0));
  REQUIRE(reference > 0.01);
}

TEST_CASE("polygon form factor: triangles meeting at a corner and at an edge, against a fine split", "[formfactor][polygon]") {
  // A floor triangle and a tilted triangle that share the corner at the origin (non-parallel edges meet there),
  // and a pair sharing an edge at 60 degrees. The whole pair equals the sum over its pieces: the first triangle
  // split into four similar triangles (midpoints), so pieces touch the other polygon at corners and edges of their own.
  const auto split = [](const std::vector<Vec3>& t) {
    const Vec3 m01 = 0.5 * (t[0] + t[1]), m12 = 0.5 * (t[1] + t[2]), m20 = 0.5 * (t[2] + t[0]);
    return std::vector<std::vector<Vec3>>{{t[0], m01, m20}, {m01, t[1], m12}, {m20, m12, t[2]}, {m01, m12, m20}};
  };
  const std::vector<Vec3> floor_tri = {{0, 0, 0}, {1, 0, 0}, {0.2, 1, 0}};
  const double c = std::cos(kPi / 3), s = std::sin(kPi / 3);
  const std::vector<std::vector<Vec3>> others = {
      {{0, 0, 0}, {-0.3, 0.2, 0.8}, {0.5, -0.1, 0.9}},        // shares the corner at the origin
      {{0, 0, 0}, {0.5, -c * 0.7, s * 0.7}, {1, 0, 0}},       // shares the edge (0,0,0)-(1,0,0), tilted 60 degrees
  };
  for (const auto& other : others) {
    const double whole = exchange_area(floor_tri, other);
    double pieces = 0;
    for (const auto& piece : split(floor_tri))
      for (const auto& piece2 : split(other)) pieces += exchange_area(piece, piece2);
    REQUIRE(whole > 1e-3);
    CHECK(pieces == Approx(whole).epsilon(1e-10).margin(0));
    CHECK(exchange_area(other, floor_tri) == Approx(whole).epsilon(1e-12).margin(0));
  }
}

TEST_CASE("polygon form factor: coplanar and back-to-back polygons give 0", "[formfactor][polygon]") {
  const auto a = floor_rect(0, 1, 0, 1, 0, true), b = floor_rect(1, 2, 0, 1, 0, true);
  CHECK(exchange_area(a, b) == 0.0);
  CHECK(exchange_area(a, floor_rect(0, 1, 0, 1, 1, true)) == 0.0);  // the upper one faces away
  CHECK(exchange_area(a, floor_rect(0, 1, 0, 1, -1, false)) == 0.0);  // below a's plane
  // Partly behind: a wall crossing the floor's plane counts only its part above (C-14 of the upper part).
  const std::vector<Vec3> crossing = wall_rect(0, 1, -0.5, 1);
  CHECK(exchange_area(floor_rect(0, 1, 0, 1, 0, true), crossing) ==
        Approx(test::perpendicular_rectangles(1, 1, 1)).epsilon(1e-10).margin(0));
}

TEST_CASE("polygon form factor: patch pairs are reciprocal bit for bit", "[formfactor][polygon]") {
  PatchBuilder builder;
  const int grey = builder.add_material("grey", Rgb(0.5, 0.5, 0.5));
  builder.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, grey);
  builder.add_triangle({0, 0, 1}, {0.3, 1, 0.8}, {1, 0.2, 1.1}, grey);
  const PatchSet ps = builder.build();
  const double g01 = patch_exchange_area(ps, 0, 1), g10 = patch_exchange_area(ps, 1, 0);
  CHECK(g01 == g10);
  CHECK(g01 > 0);
  CHECK(area_of({ps.corner(0, 0), ps.corner(0, 1), ps.corner(0, 2), ps.corner(0, 3)}) == Approx(ps.area[0]));
}

TEST_CASE("polygon form factor: every pair of a 3 x 3 cube grid equals C-11 and C-14 superposition to 1e-10",
          "[formfactor][polygon]") {
  // Every patch pair of the unit cube with 3 x 3 cells a wall (adjacent cells across an edge of the cube, cells
  // touching at a corner, collinear edges, separated cells, opposite walls) against the closed forms' algebra.
  const PatchSet ps = test::unit_cube_room(3);
  const auto rect = [&](std::size_t i) {
    test::AxisRectangle r;
    r.axis = std::abs(ps.normal[i].x()) > 0.5 ? 0 : std::abs(ps.normal[i].y()) > 0.5 ? 1 : 2;
    r.lo = r.hi = ps.corner(i, 0);
    for (int k = 1; k < 4; ++k) r.lo = r.lo.cwiseMin(ps.corner(i, k)), r.hi = r.hi.cwiseMax(ps.corner(i, k));
    r.plane = r.lo[r.axis];
    return r;
  };
  double worst = 0;
  int compared = 0;
  for (std::size_t i = 0; i < ps.size(); ++i)
    for (std::size_t j = 0; j < ps.size(); ++j) {
      const double expected = test::axis_rectangle_exchange_area(rect(i), rect(j));
      const double got = patch_exchange_area(ps, i, j);
      if (expected == 0) {
        CHECK(got == 0.0);
        continue;
      }
      ++compared;
      worst = std::max(worst, std::abs(got / expected - 1));
    }
  INFO("largest relative difference " << worst << " over " << compared << " pairs");
  CHECK(compared == 54 * 45);
  CHECK(worst <= 1e-10);
}

namespace {

// A_P F_PQ of two parallel a x b rectangles facing each other at distance c, the upper one shifted by (dx, dy),
// by the Taylor series of the kernel c^2 / (pi (c^2 + s)^2) in s = |x - y|^2 / c^2 (an independent reference for
// far pairs, where the contour terms cancel): G = (a b)^2 / (pi c^2) sum_k (-1)^k (k + 1) E[s^k] / c^(2k), with
// E[s^k] from the moments of the difference of two uniform points on [0, a] (a triangular variable with
// E[u^(2m)] = 2 a^(2m) / ((2m + 1)(2m + 2)), odd moments 0). 14 terms: exact to rounding while (a + |d|)^2 / c^2
// is below 1e-2.
double parallel_series(double a, double b, double c, double dx, double dy) {
  const int K = 14;
  const auto binom = [](int n, int k) {
    double r = 1;
    for (int i = 1; i <= k; ++i) r = r * double(n - k + i) / double(i);
    return r;
  };
  // E[(shift + u)^j], u the difference of two uniform points on [0, side].
  const auto moment = [&](double side, double shift, int j) {
    double m = 0;
    for (int i = 0; i <= j; i += 2) m += binom(j, i) * std::pow(shift, j - i) * 2 * std::pow(side, i) / ((i + 1.0) * (i + 2.0));
    return m;
  };
  double sum = 0;
  for (int k = 0; k < K; ++k) {
    double es = 0;  // E[(X^2 + Y^2)^k]
    for (int m = 0; m <= k; ++m) es += binom(k, m) * moment(a, dx, 2 * m) * moment(b, dy, 2 * (k - m));
    sum += (k % 2 ? -1.0 : 1.0) * (k + 1) * es / std::pow(c, 2 * k);
  }
  return (a * b) * (a * b) / (kPi * c * c) * sum;
}

}  // namespace

TEST_CASE("polygon form factor: far parallel rectangles equal their Taylor series to 1e-12 (the far-field rule)",
          "[formfactor][polygon]") {
  // Distances from 10 (contour integral) to 3000 sizes (far-field Gauss rule; the contour integral alone loses
  // about (c / a)^4 1e-16 there: 1e-6 relative at 300).
  for (double c : {10.0, 30.0, 100.0, 300.0, 3000.0})
    for (const auto& d : std::vector<std::array<double, 2>>{{0, 0}, {0.5, -0.25}, {0.02 * c, 0.01 * c}}) {
      const double a = 1, b = 0.5;
      const auto lower = floor_rect(0, a, 0, b, 0, true);
      const auto upper = floor_rect(d[0], d[0] + a, d[1], d[1] + b, c, false);
      const double expected = parallel_series(a, b, c, d[0], d[1]);
      // The far-field rule's pairs to 1e-12; at 10 sizes (the contour integral) to its stated 1e-10.
      const bool far = far_field_rule(lower.data(), 4, upper.data(), 4).points > 0;
      const double tolerance = far ? 1e-12 : 1e-10;
      const double e1 = std::abs(exchange_area(lower, upper) / expected - 1);
      const double e2 = std::abs(exchange_area(upper, lower) / expected - 1);
      INFO("c " << c << " shift " << d[0] << ", " << d[1] << " far " << far << " relative errors " << e1 << ", " << e2);
      CHECK(far == (c >= 30));
      CHECK(e1 <= tolerance);
      CHECK(e2 <= tolerance);
      if (c == 3000.0) {  // the contour sum alone (the route before the far-field rule) fails this test there
        double contour = 0;
        for (int e = 0; e < 4; ++e)
          for (int f = 0; f < 4; ++f)
            contour += edge_pair_log_integral(lower[std::size_t(e)], lower[std::size_t((e + 1) % 4)],
                                              upper[std::size_t(f)], upper[std::size_t((f + 1) % 4)]);
        contour /= 2 * kPi;
        CHECK(std::abs(contour / expected - 1) > 1e-9);
      }
    }
}

TEST_CASE("polygon form factor: the far-field rule agrees with the contour integral where both hold",
          "[formfactor][polygon]") {
  // Just beyond the switch (ratio about 33, distance about 26 sizes, where the contour's rounding is about
  // 26^4 1e-16 = 5e-11 relative: hence 1e-9 here) tilted quadrilaterals and triangles, by the far-field rule,
  // against the contour sum taken from edge_pair_log_integral directly.
  const auto contour = [](const std::vector<Vec3>& p, const std::vector<Vec3>& q) {
    double s = 0;
    for (std::size_t e = 0; e < p.size(); ++e)
      for (std::size_t f = 0; f < q.size(); ++f)
        s += edge_pair_log_integral(p[e], p[(e + 1) % p.size()], q[f], q[(f + 1) % q.size()]);
    return s / (2 * kPi);
  };
  const Vec3 shift(3, -2, 26);
  const std::vector<std::vector<Vec3>> lows = {
      {{0, 0, 0}, {1, 0, 0.2}, {1.1, 0.9, 0.22}, {0, 1, 0}}, {{0, 0, 0}, {1, 0.1, 0}, {0.2, 0.8, 0.3}}};
  std::vector<std::vector<Vec3>> highs;
  for (const auto& l : lows) {
    std::vector<Vec3> h;
    for (auto it = l.rbegin(); it != l.rend(); ++it) h.push_back(Vec3(it->x(), it->y(), -0.3 * it->x()) + shift);
    highs.push_back(h);
  }
  for (const auto& p : lows)
    for (const auto& q : highs) {
      const FarFieldRule rule = far_field_rule(p.data(), int(p.size()), q.data(), int(q.size()));
      INFO("corners " << p.size() << ", " << q.size() << " ratio " << rule.ratio);
      REQUIRE(rule.points > 0);
      const double expected = contour(p, q);
      CHECK(exchange_area(p, q) == Approx(expected).epsilon(1e-9).margin(0));
      CHECK(exchange_area(q, p) == Approx(expected).epsilon(1e-9).margin(0));
    }
  // Below the switch the rule says no.
  const auto near = floor_rect(0, 1, 0, 1, 5, false);
  const auto base = floor_rect(0, 1, 0, 1, 0, true);
  CHECK(far_field_rule(base.data(), 4, near.data(), 4).points == 0);
}
