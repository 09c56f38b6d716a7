#include "mesh/triangulate.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace radwalk {

namespace {

// Twice the signed area of the projected triangle (a, b, c) about the axis N: ((b - a) x (c - a)) . N.
double turn(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& N) { return (b - a).cross(c - a).dot(N); }

// p blocks the ear (a, b, c) (turning positively about N): strictly inside it, or on its diagonal c - a, where a
// cut would touch it.
bool blocks_ear(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& N) {
  return turn(a, b, p, N) > 0 && turn(b, c, p, N) > 0 && turn(c, a, p, N) >= 0;
}

// Smallest sine of the triangle's angles: its shape (sqrt(3) / 2 for an equilateral triangle, 0 for a sliver).
double shape(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double twice_area = (b - a).cross(c - a).norm();
  const double ab = (b - a).norm(), bc = (c - b).norm(), ca = (a - c).norm();
  if (!(ab > 0 && bc > 0 && ca > 0)) return 0;
  return std::min({twice_area / (ab * ca), twice_area / (ab * bc), twice_area / (bc * ca)});
}

Vec3 newell(const std::vector<Vec3>& p) {
  Vec3 N = Vec3::Zero();
  for (std::size_t k = 0; k < p.size(); ++k) N += p[k].cross(p[(k + 1) % p.size()]);
  return 0.5 * N;
}

}  // namespace

std::optional<std::vector<std::array<std::int32_t, 3>>> triangulate_polygon(const std::vector<Vec3>& corners) {
  const std::size_t n = corners.size();
  if (n < 3 || n > kMaxPolygonCorners) return std::nullopt;
  const Vec3 N = newell(corners);
  if (!(N.norm() > 0)) return std::nullopt;
  std::vector<std::int32_t> ring(n);
  for (std::size_t k = 0; k < n; ++k) ring[k] = static_cast<std::int32_t>(k);
  std::vector<std::array<std::int32_t, 3>> triangles;
  triangles.reserve(n - 2);
  while (ring.size() > 3) {
    const std::size_t m = ring.size();
    std::size_t best = m;
    double best_shape = -1;
    for (std::size_t i = 0; i < m; ++i) {
      const Vec3& a = corners[static_cast<std::size_t>(ring[(i + m - 1) % m])];
      const Vec3& b = corners[static_cast<std::size_t>(ring[i])];
      const Vec3& c = corners[static_cast<std::size_t>(ring[(i + 1) % m])];
      if (!(turn(a, b, c, N) > 0)) continue;  // a reflex or straight corner is no ear
      bool empty = true;
      for (std::size_t j = 0; j < m && empty; ++j) {
        if (j == i || j == (i + m - 1) % m || j == (i + 1) % m) continue;
        const Vec3& p = corners[static_cast<std::size_t>(ring[j])];
        if (p == a || p == b || p == c) continue;  // a repeated point (a hole's bridge) does not block
        empty = !blocks_ear(p, a, b, c, N);
      }
      if (!empty) continue;
      const double s = shape(a, b, c);
      if (s > best_shape) {
        best_shape = s;
        best = i;
      }
    }
    if (best == m) return std::nullopt;  // no ear: not a simple polygon
    triangles.push_back({ring[(best + m - 1) % m], ring[best], ring[(best + 1) % m]});
    ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(best));
  }
  if (!(turn(corners[static_cast<std::size_t>(ring[0])], corners[static_cast<std::size_t>(ring[1])],
             corners[static_cast<std::size_t>(ring[2])], N) > 0))
    return std::nullopt;
  triangles.push_back({ring[0], ring[1], ring[2]});
  return triangles;
}

std::optional<std::array<std::array<std::int32_t, 3>, 2>> split_quad(const std::array<Vec3, 4>& p) {
  const Vec3 N = newell(std::vector<Vec3>(p.begin(), p.end()));
  using Split = std::array<std::array<std::int32_t, 3>, 2>;
  const Split along02 = {{{0, 1, 2}, {0, 2, 3}}}, along13 = {{{1, 2, 3}, {1, 3, 0}}};
  auto valid = [&](const Split& s) {
    for (const auto& t : s)
      if (!(turn(p[static_cast<std::size_t>(t[0])], p[static_cast<std::size_t>(t[1])],
                 p[static_cast<std::size_t>(t[2])], N) > 0))
        return false;
    return true;
  };
  // How well the two triangles' normals agree (1: coplanar).
  auto flatness = [&](const Split& s) {
    const Vec3 n0 = (p[static_cast<std::size_t>(s[0][1])] - p[static_cast<std::size_t>(s[0][0])])
                        .cross(p[static_cast<std::size_t>(s[0][2])] - p[static_cast<std::size_t>(s[0][0])])
                        .normalized();
    const Vec3 n1 = (p[static_cast<std::size_t>(s[1][1])] - p[static_cast<std::size_t>(s[1][0])])
                        .cross(p[static_cast<std::size_t>(s[1][2])] - p[static_cast<std::size_t>(s[1][0])])
                        .normalized();
    return n0.dot(n1);
  };
  const bool a = valid(along02), b = valid(along13);
  if (a && !b) return along02;
  if (b && !a) return along13;
  if (!a && !b) return std::nullopt;
  const double fa = flatness(along02), fb = flatness(along13);
  if (std::abs(fa - fb) > 1e-12) return fa > fb ? along02 : along13;
  return (p[2] - p[0]).squaredNorm() <= (p[3] - p[1]).squaredNorm() ? along02 : along13;
}

}  // namespace radwalk
