// Ear-clipping triangulation and quad splitting: area and orientation preserved, concave and non-planar polygons,
// refusals of what cannot be triangulated.
#include <catch2/catch.hpp>

#include <cmath>

#include "mesh/triangulate.h"

using namespace radwalk;

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

}  // namespace

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
