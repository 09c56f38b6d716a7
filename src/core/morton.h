#pragma once
// Morton (Z-order) codes of points: the bits of the three coordinates, each quantised to 21 bits over a bounding
// box, interleaved (x in bit 3k, y in 3k + 1, z in 3k + 2). Points close in space mostly have close codes, so
// work visited in code order touches nearby data one after the other (caches, a BVH's nodes).
#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

#include "core/types.h"

namespace radwalk {

// The 21 low bits of v spread to every third bit of the result.
inline std::uint64_t spread_bits_by_3(std::uint64_t v) {
  v &= 0x1fffffu;
  v = (v | v << 32) & 0x1f00000000ffffull;
  v = (v | v << 16) & 0x1f0000ff0000ffull;
  v = (v | v << 8) & 0x100f00f00f00f00full;
  v = (v | v << 4) & 0x10c30c30c30c30c3ull;
  v = (v | v << 2) & 0x1249249249249249ull;
  return v;
}

// The Morton code of p in the box [lo, hi] (coordinates clamped to it; a flat axis quantises to 0).
inline std::uint64_t morton_code(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  std::uint64_t code = 0;
  for (int a = 0; a < 3; ++a) {
    const double extent = hi[a] - lo[a];
    const double t = extent > 0 ? std::clamp((p[a] - lo[a]) / extent, 0.0, 1.0) : 0.0;
    code |= spread_bits_by_3(std::uint64_t(t * double(0x1fffff))) << a;
  }
  return code;
}

// The indices first, ..., last - 1 of `points` ordered by Morton code over the points' bounding box, ties by index:
// a permutation that depends only on the points.
inline std::vector<std::uint32_t> morton_order(const std::vector<Vec3>& points, std::size_t first, std::size_t last) {
  std::vector<std::uint32_t> order(last - first);
  if (order.empty()) return order;
  Vec3 lo = points[first], hi = points[first];
  for (std::size_t i = first; i < last; ++i) {
    lo = lo.cwiseMin(points[i]);
    hi = hi.cwiseMax(points[i]);
  }
  std::vector<std::uint64_t> code(last - first);
  for (std::size_t i = first; i < last; ++i) code[i - first] = morton_code(points[i], lo, hi);
  std::iota(order.begin(), order.end(), std::uint32_t(first));
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return code[a - first] != code[b - first] ? code[a - first] < code[b - first] : a < b;
  });
  return order;
}

}  // namespace radwalk
