// Ear-clipping triangulation and quad splitting: area and orientation preserved, concave and non-planar polygons,
// refusals of what cannot be triangulated.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <optional>
#include <random>

#include "mesh/triangulate.h"
#include "support/full_scan_ear_clipping.h"

using namespace radwalk;
using radwalk::test::full_scan_ear_clipping;

namespace {

Vec3 newell(const std::vector<Vec3>& p) {
  Vec3 N = Vec3::Zero();
  for (std::size_t k = 0; k < p.size(); ++k) N += p[k].cross(p[(k + 1) % p.size()]);
  return 0.5 * N;
}

// Sum of the triangles' areas, and whether each turns along N.
struct Tiling {
  double area = 0;
  bool oriented = true;
  std::size_t count = 0;
};
Tiling tiling(const std::vector<Vec3>& p, const std::vector<std::array<std::int32_t, 3>>& t) {
  const Vec3 N = newell(p);
  Tiling r;
  for (const auto& tri : t) {
    const Vec3 v = 0.5 * (p[static_cast<std::size_t>(tri[1])] - p[static_cast<std::size_t>(tri[0])])
                             .cross(p[static_cast<std::size_t>(tri[2])] - p[static_cast<std::size_t>(tri[0])]);
    r.area += v.norm();
    r.oriented = r.oriented && v.dot(N) > 0;
    ++r.count;
  }
  return r;
}


// The n-gons of the cost test, in the plane z = 0 about the origin (radius at most 1): regular (convex), a star
// (radii 1 and 0.5 alternating: n / 2 reflex corners) and a comb (teeth of depth 0.9 on a bar: about n / 2 reflex).
std::vector<Vec3> regular_polygon(std::size_t n) {
  std::vector<Vec3> p;
  for (std::size_t k = 0; k < n; ++k) {
    const double a = 2 * M_PI * static_cast<double>(k) / static_cast<double>(n);
    p.emplace_back(std::cos(a), std::sin(a), 0);
  }
  return p;
}
std::vector<Vec3> star_polygon(std::size_t n) {
  std::vector<Vec3> p = regular_polygon(n);
  for (std::size_t k = 1; k < n; k += 2) p[k] *= 0.5;
  return p;
}
std::vector<Vec3> comb_polygon(std::size_t n) {  // n a multiple of 4
  const std::size_t teeth = (n - 4) / 4 + 1;
  const double w = 1.0 / static_cast<double>(teeth);  // a tooth and its gap in x in [-0.5, 0.5]
  std::vector<Vec3> p = {{-0.5, -0.5, 0}, {0.5, -0.5, 0}};
  for (std::size_t k = teeth; k-- > 0;) {
    const double x = -0.5 + w * static_cast<double>(k);
    p.emplace_back(x + w, 0.5, 0);
    p.emplace_back(x + 0.5 * w, 0.5, 0);
    if (k > 0) {
      p.emplace_back(x + 0.5 * w, -0.4, 0);
      p.emplace_back(x, -0.4, 0);
    }
  }
  return p;
}

// Twice the shoelace area in z = 0.
double shoelace(const std::vector<Vec3>& p) {
  double s = 0;
  for (std::size_t k = 0; k < p.size(); ++k) s += p[k].x() * p[(k + 1) % p.size()].y() - p[k].y() * p[(k + 1) % p.size()].x();
  return 0.5 * s;
}

}  // namespace

TEST_CASE("a convex, a star and a comb 4096-gon are triangulated to their shoelace area with O(n) ear tests",
          "[mesh][triangulate]") {
  // Ear lists: cutting an ear re-tests only its two neighbours (plus the cut ear once more), so there are at most
  // 4 n ear tests; each looks at the reflex corners only: none for a convex polygon, at most r per test otherwise.
  // The former full scan made about n^2 / 2 ear tests and n^3 / 6 corner tests (22 CPU s at n = 2048).
  constexpr double u = std::numeric_limits<double>::epsilon() / 2;
  const std::size_t n = kMaxPolygonCorners;
  for (const auto& [name, p] : {std::pair<const char*, std::vector<Vec3>>{"convex", regular_polygon(n)},
                                {"star", star_polygon(n)}, {"comb", comb_polygon(n)}}) {
    INFO(name << " " << p.size() << "-gon");
    REQUIRE(p.size() == n);
    std::size_t reflex = 0;
    for (std::size_t k = 0; k < n; ++k)
      reflex += (p[k] - p[(k + n - 1) % n]).cross(p[(k + 1) % n] - p[k]).z() <= 0;
    TriangulationCost cost;
    const auto t = triangulate_polygon(p, &cost);
    REQUIRE(t);
    const Tiling r = tiling(p, *t);
    CHECK(r.count == n - 2);
    CHECK(r.oriented);
    // Coordinates at most R = 1: each triangle's area (two differences, a cross product, a norm) is within 4 u R^2
    // of exact, the shoelace's n terms within 2 u R^2 each, and the sums add n u (area) more: 8 n u R^2 in all.
    CHECK(std::abs(r.area - shoelace(p)) <= 8 * static_cast<double>(n) * u);
    CHECK(cost.ear_tests <= 4 * n);
    CHECK(cost.blocker_tests <= cost.ear_tests * reflex);
    if (reflex == 0) CHECK(cost.blocker_tests == 0);
  }
}

TEST_CASE("ear lists give the triangles of the former full-scan ear clipping", "[mesh][triangulate]") {
  // The triangles radwalk made before must stay (tests and outputs compare them): random star-shaped polygons of
  // 5 to 120 corners (concave), regular polygons (many equally good ears: ties go to the lowest corner) and the
  // cost test's star and comb at small n.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> radius(0.2, 1.0);
  std::vector<std::vector<Vec3>> polygons;
  for (int trial = 0; trial < 200; ++trial) {
    const std::size_t n = 5 + static_cast<std::size_t>(trial) % 116;
    std::vector<Vec3> p;
    for (std::size_t k = 0; k < n; ++k) {
      const double a = 2 * M_PI * static_cast<double>(k) / static_cast<double>(n), r = radius(rng);
      p.emplace_back(r * std::cos(a), r * std::sin(a), 0.1 * r * std::cos(3 * a));  // slightly non-planar too
    }
    polygons.push_back(p);
  }
  for (std::size_t n : {5, 6, 12, 64}) polygons.push_back(regular_polygon(n));
  for (std::size_t n : {8, 16, 64}) {
    polygons.push_back(star_polygon(n));
    polygons.push_back(comb_polygon(n));
  }
  for (const auto& p : polygons) {
    INFO(p.size() << " corners");
    const auto reference = full_scan_ear_clipping(p);
    const auto t = triangulate_polygon(p);
    REQUIRE(reference.has_value() == t.has_value());
    if (t) CHECK(*t == *reference);
  }
}

TEST_CASE("ear clipping tiles convex and concave planar polygons exactly, keeping their orientation", "[mesh][triangulate]") {
  // A regular 64-gon, an L-shaped hexagon, a 5-pointed star (10 corners), a comb, all in a tilted plane.
  const Vec3 u = Vec3(1, 0.2, 0.1).normalized(), w = Vec3(0, 1, 0).cross(u).normalized(), v = w.cross(u);
  auto plane = [&](double x, double y) -> Vec3 { return Vec3(3, -2, 5) + x * u + y * v; };  // a Vec3, not an expression of temporaries
  std::vector<std::vector<Vec3>> polygons;
  std::vector<Vec3> circle;
  for (int k = 0; k < 64; ++k) circle.push_back(plane(std::cos(2 * M_PI * k / 64), std::sin(2 * M_PI * k / 64)));
  polygons.push_back(circle);
  polygons.push_back({plane(0, 0), plane(2, 0), plane(2, 1), plane(1, 1), plane(1, 2), plane(0, 2)});
  std::vector<Vec3> star;
  for (int k = 0; k < 10; ++k) {
    const double r = k % 2 ? 0.4 : 1.0, a = M_PI / 2 + M_PI * k / 5;
    star.push_back(plane(r * std::cos(a), r * std::sin(a)));
  }
  polygons.push_back(star);
  std::vector<Vec3> comb = {plane(0, 0), plane(7, 0)};
  for (int k = 7; k >= 1; --k) {
    comb.push_back(plane(k, 3));
    comb.push_back(plane(k - 0.5, 3));
    comb.push_back(plane(k - 0.5, 1));
    comb.push_back(plane(k - 1, 1));
  }
  polygons.push_back(comb);
  // Reversed orientation too: the triangles must follow it.
  for (std::size_t k = 0, n = polygons.size(); k < n; ++k)
    polygons.emplace_back(polygons[k].rbegin(), polygons[k].rend());
  for (const auto& p : polygons) {
    INFO(p.size() << " corners");
    const auto t = triangulate_polygon(p);
    REQUIRE(t);
    const Tiling r = tiling(p, *t);
    CHECK(r.count == p.size() - 2);
    CHECK(r.oriented);
    CHECK(r.area == Approx(newell(p).norm()).epsilon(1e-12));
  }
}

TEST_CASE("ear clipping splits a non-planar polygon into planar triangles", "[mesh][triangulate]") {
  // A hexagon on a saddle z = x y: every triangle is planar by construction, the orientation follows Newell's.
  std::vector<Vec3> p;
  for (int k = 0; k < 6; ++k) {
    const double a = 2 * M_PI * k / 6, x = std::cos(a), y = std::sin(a);
    p.emplace_back(x, y, 0.3 * x * y);
  }
  const auto t = triangulate_polygon(p);
  REQUIRE(t);
  CHECK(t->size() == 4);
  CHECK(tiling(p, *t).oriented);
}

TEST_CASE("what has no orientation or is not simple is not triangulated", "[mesh][triangulate]") {
  CHECK(!triangulate_polygon({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}));             // collinear
  CHECK(!triangulate_polygon({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {2, 1, 0}}));  // a bow-tie: zero vector area
  // A figure-eight whose lobes differ: it has an orientation, but the smaller lobe's corners never become ears.
  CHECK(!triangulate_polygon({{0, 0, 0}, {2, 2, 0}, {2, 0, 0}, {0, 2, 0}, {-1, 2, 0}, {-1, 0, 0}}).has_value());
  CHECK(!triangulate_polygon(std::vector<Vec3>(kMaxPolygonCorners + 1, Vec3::Zero())));
}

TEST_CASE("split_quad cuts inside a concave quad and along the flatter diagonal of a non-planar one", "[mesh][triangulate]") {
  // Concave (a dart): the reflex corner is 2, so only the diagonal 0-2 keeps both triangles inside.
  const std::array<Vec3, 4> dart = {Vec3(0, 0, 0), Vec3(2, -1, 0), Vec3(1, 0, 0), Vec3(2, 1, 0)};
  const auto d = split_quad(dart);
  REQUIRE(d);
  CHECK((*d)[0] == std::array<std::int32_t, 3>{0, 1, 2});
  CHECK((*d)[1] == std::array<std::int32_t, 3>{0, 2, 3});
  // Non-planar: corner 2 lifted; both diagonals are valid, and the two choices bend differently.
  const std::array<Vec3, 4> bent = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0.4), Vec3(0, 1, 0)};
  const auto b = split_quad(bent);
  REQUIRE(b);
  CHECK((*b)[0] == std::array<std::int32_t, 3>{1, 2, 3});  // the lifted corner's two neighbours joined
  // A bow-tie: neither diagonal gives two properly oriented triangles.
  CHECK(!split_quad({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(2, 1, 0)}));
}
