#include "mesh/triangulate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

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

std::optional<std::vector<std::array<std::int32_t, 3>>> triangulate_polygon(const std::vector<Vec3>& corners,
                                                                            TriangulationCost* cost) {
  const std::size_t n = corners.size();
  if (n < 3 || n > kMaxPolygonCorners) return std::nullopt;
  const Vec3 N = newell(corners);
  if (!(N.norm() > 0)) return std::nullopt;
  TriangulationCost local;
  TriangulationCost& count = cost ? *cost : local;
  auto at = [&](std::int32_t k) -> const Vec3& { return corners[static_cast<std::size_t>(k)]; };

  // The ring as a doubly linked list over the corners' indices (ring order = increasing index, as cut).
  std::vector<std::int32_t> prev(n), next(n);
  for (std::size_t k = 0; k < n; ++k) {
    prev[k] = static_cast<std::int32_t>((k + n - 1) % n);
    next[k] = static_cast<std::int32_t>((k + 1) % n);
  }
  std::vector<char> alive(n, 1);
  // Corners that are not strictly convex (reflex or straight): the only ones that can block an ear (in a simple
  // polygon, a triangle (a, b, c) at a convex corner b that holds any corner holds a reflex one: the one farthest
  // from the diagonal c - a). `reflex_list` may hold corners since cut or turned convex (skipped, then dropped).
  std::vector<char> reflex(n, 0);
  std::vector<std::int32_t> reflex_list;
  auto convex = [&](std::int32_t b) { return turn(at(prev[static_cast<std::size_t>(b)]), at(b), at(next[static_cast<std::size_t>(b)]), N) > 0; };
  for (std::size_t k = 0; k < n; ++k)
    if (!convex(static_cast<std::int32_t>(k))) {
      reflex[k] = 1;
      reflex_list.push_back(static_cast<std::int32_t>(k));
    }
  std::size_t stale = 0;  // entries of reflex_list no longer alive and reflex

  // Corner b is an ear: convex, and no reflex corner strictly inside its triangle or on its diagonal.
  auto is_ear = [&](std::int32_t b) {
    ++count.ear_tests;
    const std::int32_t ia = prev[static_cast<std::size_t>(b)], ic = next[static_cast<std::size_t>(b)];
    const Vec3 &a = at(ia), &pb = at(b), &c = at(ic);
    if (!(turn(a, pb, c, N) > 0)) return false;  // a reflex or straight corner is no ear
    for (const std::int32_t j : reflex_list) {
      if (!alive[static_cast<std::size_t>(j)] || !reflex[static_cast<std::size_t>(j)] || j == ia || j == ic) continue;
      ++count.blocker_tests;
      const Vec3& p = at(j);
      if (p == a || p == pb || p == c) continue;  // a repeated point (a hole's bridge) does not block
      if (blocks_ear(p, a, pb, c, N)) return false;
    }
    return true;
  };

  // Candidate ears, best shape first, ties to the lowest corner index (the order of the former full scan, which
  // cut the best-shaped ear, the first in ring order among equals). An entry is current while its version matches.
  struct Candidate {
    double shape;
    std::int32_t corner;
    std::uint32_t version;
  };
  auto worse = [](const Candidate& x, const Candidate& y) {
    return x.shape != y.shape ? x.shape < y.shape : x.corner > y.corner;
  };
  std::priority_queue<Candidate, std::vector<Candidate>, decltype(worse)> ears(worse);
  std::vector<std::uint32_t> version(n, 0);
  auto consider = [&](std::int32_t b) {
    const auto k = static_cast<std::size_t>(b);
    ++version[k];
    if (!is_ear(b)) return;
    const double s = shape(at(prev[k]), at(b), at(next[k]));
    if (!(s >= 0)) return;  // not a number: never cut (as the full scan never chose it)
    ears.push({s, b, version[k]});
  };
  for (std::size_t k = 0; k < n; ++k) consider(static_cast<std::int32_t>(k));

  std::vector<std::array<std::int32_t, 3>> triangles;
  triangles.reserve(n - 2);
  std::size_t remaining = n, rescans = 0;
  std::int32_t first = 0;  // a corner still in the ring
  while (remaining > 3) {
    if (ears.empty()) {
      // In exact arithmetic an ear's status changes only when a neighbour is cut, so this is a polygon that is
      // not simple. Rounding can hide an ear from that rule: look again at every corner, a bounded number of times.
      if (rescans++ == kMaxEarRescans) return std::nullopt;
      std::int32_t k = first;
      for (std::size_t m = 0; m < remaining; ++m, k = next[static_cast<std::size_t>(k)]) consider(k);
      if (ears.empty()) return std::nullopt;  // no ear: not a simple polygon
    }
    const Candidate best = ears.top();
    ears.pop();
    const auto b = static_cast<std::size_t>(best.corner);
    if (!alive[b] || best.version != version[b]) continue;
    if (!is_ear(best.corner)) {  // rounding: a corner turned reflex since; it is looked at again when it changes
      ++version[b];
      continue;
    }
    const std::int32_t a = prev[b], c = next[b];
    triangles.push_back({a, best.corner, c});
    alive[b] = 0;
    next[static_cast<std::size_t>(a)] = c;
    prev[static_cast<std::size_t>(c)] = a;
    first = a;
    --remaining;
    // The two neighbours: each may have turned convex (or, by rounding, reflex), and their ears changed.
    for (const std::int32_t v : {a, c}) {
      const auto k = static_cast<std::size_t>(v);
      const bool r = !convex(v);
      if (r && !reflex[k]) reflex_list.push_back(v);
      if (!r && reflex[k]) ++stale;
      reflex[k] = r;
    }
    if (reflex[b]) ++stale;
    if (2 * stale > reflex_list.size() && stale > 0) {
      reflex_list.erase(std::remove_if(reflex_list.begin(), reflex_list.end(),
                                       [&](std::int32_t j) {
                                         return !alive[static_cast<std::size_t>(j)] ||
                                                !reflex[static_cast<std::size_t>(j)];
                                       }),
                        reflex_list.end());
      stale = 0;
    }
    if (remaining > 3) {
      consider(a);
      consider(c);
    }
  }
  const std::int32_t r0 = first, r1 = next[static_cast<std::size_t>(r0)], r2 = next[static_cast<std::size_t>(r1)];
  std::array<std::int32_t, 3> last = {r0, r1, r2};
  std::sort(last.begin(), last.end());  // ring order from the lowest index, as the former vector ring had it
  if (!(turn(at(last[0]), at(last[1]), at(last[2]), N) > 0)) return std::nullopt;
  triangles.push_back(last);
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
