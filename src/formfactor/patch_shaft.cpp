#include "formfactor/patch_shaft.h"

#include <algorithm>
#include <cmath>

namespace radwalk {
namespace {

struct Plane {
  Vec3 n;  // outward unit normal
  double offset = 0;  // n . x = offset on the plane
  double distance(const Vec3& x) const { return n.dot(x) - offset; }
};

constexpr int kMaxPlanes = 2 + 2 * kMaxPolygonCorners * kMaxPolygonCorners;

// The face planes of the hull of the two clipped polygons (see patch_shaft.h), outward normals.
int shaft_planes(const ClippedPair& pair, const Vec3& n_i, const Vec3& n_j, double tol, Plane* planes) {
  int m = 0;
  planes[m++] = {-n_i, -n_i.dot(pair.p[0])};
  planes[m++] = {-n_j, -n_j.dot(pair.q[0])};
  const auto consider = [&](const Vec3* poly, int count, const Vec3* other, int other_count) {
    for (int e = 0; e < count; ++e) {
      const Vec3& a = poly[e];
      const Vec3& b = poly[(e + 1) % count];
      for (int c = 0; c < other_count; ++c) {
        Vec3 n = (b - a).cross(other[c] - a);
        const double len = n.norm();
        if (!(len > 0)) continue;
        n /= len;
        const double off = n.dot(a);
        bool all_below = true, all_above = true;
        for (int k = 0; k < pair.np && (all_below || all_above); ++k) {
          const double s = n.dot(pair.p[k]) - off;
          all_below = all_below && s <= tol;
          all_above = all_above && s >= -tol;
        }
        for (int k = 0; k < pair.nq && (all_below || all_above); ++k) {
          const double s = n.dot(pair.q[k]) - off;
          all_below = all_below && s <= tol;
          all_above = all_above && s >= -tol;
        }
        if (all_below && all_above) continue;  // everything on the plane: the pair is coplanar (never a shaft)
        if (!all_below && !all_above) continue;
        const Plane plane = all_below ? Plane{n, off} : Plane{-n, -off};
        bool known = false;  // the same face found from another edge and corner
        for (int k = 0; k < m && !known; ++k)
          known = planes[k].n.dot(plane.n) > 1 - 1e-12 && std::abs(planes[k].offset - plane.offset) <= tol;
        if (!known) planes[m++] = plane;
      }
    }
  };
  consider(pair.p, pair.np, pair.q, pair.nq);
  consider(pair.q, pair.nq, pair.p, pair.np);
  return m;
}

bool box_outside(const Vec3& lo, const Vec3& hi, const Plane* planes, int m, double tol) {
  const Vec3 c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
  for (int k = 0; k < m; ++k) {
    const Plane& p = planes[k];
    if (p.distance(c) - (std::abs(p.n.x()) * h.x() + std::abs(p.n.y()) * h.y() + std::abs(p.n.z()) * h.z()) >= -tol)
      return true;
  }
  return false;
}

}  // namespace

PatchShaftTest::PatchShaftTest(const PatchSet& patches) : patches_(patches) {
  const std::size_t N = patches.size();
  tolerance_ = 1e-9 * std::max(patches.scene_extent(), 1e-300);
  std::vector<Vec3> lo(N), hi(N), centre(N);
  convex_.resize(N);
  for (std::size_t i = 0; i < N; ++i) {
    lo[i] = hi[i] = patches.corner(i, 0);
    const int count = patches.corner_count(i);
    bool convex = true;
    for (int k = 0; k < count; ++k) {
      const Vec3& c = patches.corner(i, k);
      lo[i] = lo[i].cwiseMin(c);
      hi[i] = hi[i].cwiseMax(c);
      const Vec3& a = patches.corner(i, (k + count - 1) % count);
      const Vec3& b = patches.corner(i, (k + 1) % count);
      convex = convex && (c - a).cross(b - c).dot(patches.normal[i]) > 0;
    }
    convex_[i] = convex;
    centre[i] = 0.5 * (lo[i] + hi[i]);
  }
  order_.resize(N);
  for (std::size_t i = 0; i < N; ++i) order_[i] = std::int32_t(i);
  nodes_.reserve(2 * N / 2 + 2);
  if (N > 0) build(0, std::int32_t(N), lo, hi, centre);
}

std::int32_t PatchShaftTest::build(std::int32_t first, std::int32_t count, const std::vector<Vec3>& lo,
                                   const std::vector<Vec3>& hi, const std::vector<Vec3>& centre) {
  const std::int32_t index = std::int32_t(nodes_.size());
  nodes_.emplace_back();
  Vec3 blo = lo[order_[first]], bhi = hi[order_[first]], clo = centre[order_[first]], chi = clo;
  for (std::int32_t k = first; k < first + count; ++k) {
    blo = blo.cwiseMin(lo[order_[k]]);
    bhi = bhi.cwiseMax(hi[order_[k]]);
    clo = clo.cwiseMin(centre[order_[k]]);
    chi = chi.cwiseMax(centre[order_[k]]);
  }
  nodes_[index].lo = blo;
  nodes_[index].hi = bhi;
  if (count <= 4) {
    nodes_[index].first = first;
    nodes_[index].count = count;
    return index;
  }
  int axis = 0;
  const Vec3 span = chi - clo;
  if (span.y() > span[axis]) axis = 1;
  if (span.z() > span[axis]) axis = 2;
  const std::int32_t half = count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                   [&](std::int32_t a, std::int32_t b) {
                     return centre[a][axis] < centre[b][axis] || (centre[a][axis] == centre[b][axis] && a < b);
                   });
  const std::int32_t left = build(first, half, lo, hi, centre);
  const std::int32_t right = build(first + half, count - half, lo, hi, centre);
  nodes_[index].left = left;
  nodes_[index].right = right;
  return index;
}

ShaftResult PatchShaftTest::classify(std::size_t i, std::size_t j, const ClippedPair& pair) const {
  if (nodes_.empty()) return ShaftResult::clear;
  const double tol = tolerance_;
  Plane planes[kMaxPlanes];
  const int m = shaft_planes(pair, patches_.normal[i], patches_.normal[j], tol, planes);
  Vec3 slo = pair.p[0], shi = pair.p[0];
  for (int k = 0; k < pair.np; ++k) slo = slo.cwiseMin(pair.p[k]), shi = shi.cwiseMax(pair.p[k]);
  for (int k = 0; k < pair.nq; ++k) slo = slo.cwiseMin(pair.q[k]), shi = shi.cwiseMax(pair.q[k]);

  bool maybe = false;
  std::int32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[std::size_t(stack[--top])];
    if ((node.lo.array() > shi.array() + tol).any() || (node.hi.array() < slo.array() - tol).any()) continue;
    if (box_outside(node.lo, node.hi, planes, m, tol)) continue;
    if (node.left >= 0) {
      stack[top++] = node.left;
      stack[top++] = node.right;
      continue;
    }
    for (std::int32_t q = node.first; q < node.first + node.count; ++q) {
      const std::size_t k = std::size_t(order_[std::size_t(q)]);
      if (k == i || k == j) continue;
      const int count = patches_.corner_count(k);
      Vec3 c[4];
      for (int a = 0; a < count; ++a) c[a] = patches_.corner(k, a);
      // (a) k on or beyond a face plane of the shaft.
      bool outside = false;
      for (int f = 0; f < m && !outside; ++f) {
        bool all = true;
        for (int a = 0; a < count && all; ++a) all = planes[f].distance(c[a]) >= -tol;
        outside = all;
      }
      if (outside) continue;
      // (b) k's plane with the whole shaft on one side; otherwise remember the signs for the cover test.
      const Vec3& nk = patches_.normal[k];
      double sp[kMaxPolygonCorners], sq[kMaxPolygonCorners];
      bool below = true, above = true;
      for (int a = 0; a < pair.np; ++a) {
        sp[a] = nk.dot(pair.p[a] - c[0]);
        below = below && sp[a] <= tol;
        above = above && sp[a] >= -tol;
      }
      for (int a = 0; a < pair.nq; ++a) {
        sq[a] = nk.dot(pair.q[a] - c[0]);
        below = below && sq[a] <= tol;
        above = above && sq[a] >= -tol;
      }
      if (below || above) continue;
      maybe = true;
      // Cover: k convex, its plane strictly between the polygons, every corner-to-corner crossing inside k.
      if (!convex_[k]) continue;
      bool p_front = true, p_back = true, q_front = true, q_back = true;
      for (int a = 0; a < pair.np; ++a) p_front = p_front && sp[a] > tol, p_back = p_back && sp[a] < -tol;
      for (int a = 0; a < pair.nq; ++a) q_front = q_front && sq[a] > tol, q_back = q_back && sq[a] < -tol;
      if (!((p_front && q_back) || (p_back && q_front))) continue;
      bool covers = true;
      for (int a = 0; a < pair.np && covers; ++a)
        for (int b = 0; b < pair.nq && covers; ++b) {
          const double t = sp[a] / (sp[a] - sq[b]);
          const Vec3 x = pair.p[a] + t * (pair.q[b] - pair.p[a]);
          for (int e = 0; e < count && covers; ++e) {
            const Vec3 edge = c[(e + 1) % count] - c[e];
            covers = edge.cross(x - c[e]).dot(nk) > tol * edge.norm();
          }
        }
      if (covers) return ShaftResult::hidden;
    }
  }
  return maybe ? ShaftResult::maybe_blocked : ShaftResult::clear;
}

}  // namespace radwalk
