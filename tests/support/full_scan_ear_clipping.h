#pragma once
// The former ear clipping of mesh/triangulate.h, kept as a reference: the tests check that ear lists give the same
// triangles, and bench_polygons times it beside the current one.
#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/types.h"

namespace radwalk::test {

// The former ear clipping, kept as the reference of the triangles radwalk gave before ear lists: every round
// tests every corner against every other corner and cuts the best-shaped ear, the first in ring order among
// equals (O(n^3)).
inline std::optional<std::vector<std::array<std::int32_t, 3>>> full_scan_ear_clipping(const std::vector<Vec3>& corners) {
  auto turn = [](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& N) { return (b - a).cross(c - a).dot(N); };
  auto shape = [](const Vec3& a, const Vec3& b, const Vec3& c) {
    const double twice_area = (b - a).cross(c - a).norm();
    const double ab = (b - a).norm(), bc = (c - b).norm(), ca = (a - c).norm();
    if (!(ab > 0 && bc > 0 && ca > 0)) return 0.0;
    return std::min({twice_area / (ab * ca), twice_area / (ab * bc), twice_area / (bc * ca)});
  };
  const std::size_t n = corners.size();
  Vec3 N = Vec3::Zero();
  for (std::size_t k = 0; k < n; ++k) N += 0.5 * corners[k].cross(corners[(k + 1) % n]);
  if (!(N.norm() > 0)) return std::nullopt;
  std::vector<std::int32_t> ring(n);
  for (std::size_t k = 0; k < n; ++k) ring[k] = static_cast<std::int32_t>(k);
  std::vector<std::array<std::int32_t, 3>> triangles;
  auto at = [&](std::size_t i) -> const Vec3& { return corners[static_cast<std::size_t>(ring[i])]; };
  while (ring.size() > 3) {
    const std::size_t m = ring.size();
    std::size_t best = m;
    double best_shape = -1;
    for (std::size_t i = 0; i < m; ++i) {
      const Vec3 &a = at((i + m - 1) % m), &b = at(i), &c = at((i + 1) % m);
      if (!(turn(a, b, c, N) > 0)) continue;
      bool empty = true;
      for (std::size_t j = 0; j < m && empty; ++j) {
        if (j == i || j == (i + m - 1) % m || j == (i + 1) % m) continue;
        const Vec3& p = at(j);
        if (p == a || p == b || p == c) continue;
        empty = !(turn(a, b, p, N) > 0 && turn(b, c, p, N) > 0 && turn(c, a, p, N) >= 0);
      }
      if (!empty) continue;
      const double s = shape(a, b, c);
      if (s > best_shape) {
        best_shape = s;
        best = i;
      }
    }
    if (best == m) return std::nullopt;
    triangles.push_back({ring[(best + m - 1) % m], ring[best], ring[(best + 1) % m]});
    ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(best));
  }
  if (!(turn(at(0), at(1), at(2), N) > 0)) return std::nullopt;
  triangles.push_back({ring[0], ring[1], ring[2]});
  return triangles;
}

}  // namespace radwalk::test
