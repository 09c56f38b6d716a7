#include "hierarchy/element_tree.h"

#include <algorithm>
#include <limits>

#include "core/check.h"
#include "core/sampling.h"

namespace radwalk {

double element_area(const std::array<Vec3, 4>& c, int count) {
  double a = 0.5 * (c[1] - c[0]).cross(c[2] - c[0]).norm();
  if (count == 4) a += 0.5 * (c[2] - c[0]).cross(c[3] - c[0]).norm();
  return a;
}

ElementTree make_element_tree(const PatchSet& patches) {
  ElementTree t;
  const std::size_t n = patches.size();
  t.corner.resize(n);
  t.corner_count.resize(n);
  t.root.resize(n);
  t.parent.assign(n, -1);
  t.first_child.assign(n, -1);
  t.level.assign(n, 0);
  t.area.resize(n);
  t.split_kind.assign(n, SplitKind::regular);
  for (std::size_t i = 0; i < n; ++i) {
    const int k = patches.corner_count(i);
    t.corner_count[i] = static_cast<std::int8_t>(k);
    for (int c = 0; c < k; ++c) t.corner[i][static_cast<std::size_t>(c)] = patches.corner(i, c);
    if (k == 3) t.corner[i][3] = t.corner[i][0];
    t.root[i] = static_cast<std::int32_t>(i);
    t.area[i] = patches.area[i];
  }
  return t;
}

ElementIndex ElementTree::split(std::size_t e, SplitKind kind) {
  RADWALK_CHECK(e < size());
  RADWALK_CHECK(first_child[e] < 0);
  const std::array<Vec3, 4> c = corner[e];
  const int k = corner_count[e];
  RADWALK_CHECK(kind == SplitKind::regular || k == 4);
  std::array<std::array<Vec3, 4>, 4> child;
  if (kind != SplitKind::regular) {
    // Bands: the cuts join a0 + t (a1 - a0) to b0 + t (b1 - b0), t = 1/4, 1/2, 3/4, each point a midpoint of
    // midpoints (symmetric in the edge's ends, bit-identical with a neighbour's).
    const bool b01 = kind == SplitKind::bands_01;
    const Vec3 &a0 = c[0], &a1 = b01 ? c[1] : c[3], &b0 = b01 ? c[3] : c[1], &b1 = c[2];
    const Vec3 pa2 = 0.5 * (a0 + a1), pb2 = 0.5 * (b0 + b1);
    const Vec3 pa1 = 0.5 * (a0 + pa2), pa3 = 0.5 * (pa2 + a1), pb1 = 0.5 * (b0 + pb2), pb3 = 0.5 * (pb2 + b1);
    const std::array<Vec3, 5> pa{a0, pa1, pa2, pa3, a1}, pb{b0, pb1, pb2, pb3, b1};
    for (std::size_t q = 0; q < 4; ++q)
      // Counter-clockwise as the parent: along a (c0 -> c1) then b back for bands_01; for bands_12 the a edge is
      // c0 -> c3, which runs clockwise, so the child is (a_q, b_q, b_q+1, a_q+1).
      child[q] = b01 ? std::array<Vec3, 4>{pa[q], pa[q + 1], pb[q + 1], pb[q]}
                     : std::array<Vec3, 4>{pa[q], pb[q], pb[q + 1], pa[q + 1]};
  } else if (k == 4) {
    const Vec3 m01 = 0.5 * (c[0] + c[1]), m12 = 0.5 * (c[1] + c[2]), m23 = 0.5 * (c[2] + c[3]),
               m30 = 0.5 * (c[3] + c[0]);
    const Vec3 m = 0.25 * (c[0] + c[1] + c[2] + c[3]);
    child = {{{c[0], m01, m, m30}, {m01, c[1], m12, m}, {m, m12, c[2], m23}, {m30, m, m23, c[3]}}};
  } else {
    const Vec3 m01 = 0.5 * (c[0] + c[1]), m12 = 0.5 * (c[1] + c[2]), m20 = 0.5 * (c[2] + c[0]);
    child = {{{c[0], m01, m20, c[0]}, {m01, c[1], m12, m01}, {m20, m12, c[2], m20}, {m01, m12, m20, m01}}};
  }
  const auto first = static_cast<ElementIndex>(size());
  RADWALK_CHECK(size() + 4 < static_cast<std::size_t>(std::numeric_limits<ElementIndex>::max()));
  for (std::size_t q = 0; q < 4; ++q) {
    corner.push_back(child[q]);
    corner_count.push_back(static_cast<std::int8_t>(k));
    root.push_back(root[e]);
    parent.push_back(static_cast<ElementIndex>(e));
    first_child.push_back(-1);
    level.push_back(static_cast<std::int16_t>(level[e] + 1));
    area.push_back(element_area(child[q], k));
  }
  first_child[e] = first;
  split_kind.resize(size(), SplitKind::regular);
  split_kind[e] = kind;
  return first;
}

ElementIndex ElementTree::child_containing(std::size_t e, const Vec3& p, const Vec3& normal) const {
  RADWALK_CHECK(first_child[e] >= 0);
  // Fast path: a child that holds p strictly inside (every signed distance > 0; the sign needs no edge length) is
  // the answer, since the children's interiors are disjoint and every other child then has a distance <= 0.
  for (ElementIndex q = first_child[e]; q < first_child[e] + 4; ++q) {
    const auto& c = corner[static_cast<std::size_t>(q)];
    const int k = corner_count[static_cast<std::size_t>(q)];
    bool strictly_inside = true;
    for (int a = 0; a < k && strictly_inside; ++a) {
      const Vec3& p0 = c[static_cast<std::size_t>(a)];
      const Vec3 edge = c[static_cast<std::size_t>((a + 1) % k)] - p0;
      strictly_inside = edge.squaredNorm() > 0 && edge.cross(p - p0).dot(normal) > 0;
    }
    if (strictly_inside) return q;
  }
  ElementIndex best = first_child[e];
  double best_inside = -std::numeric_limits<double>::infinity();
  for (ElementIndex q = first_child[e]; q < first_child[e] + 4; ++q) {
    const auto& c = corner[static_cast<std::size_t>(q)];
    const int k = corner_count[static_cast<std::size_t>(q)];
    double inside = std::numeric_limits<double>::infinity();
    for (int a = 0; a < k; ++a) {
      const Vec3& p0 = c[static_cast<std::size_t>(a)];
      const Vec3& p1 = c[static_cast<std::size_t>((a + 1) % k)];
      const Vec3 edge = p1 - p0;
      const double len = edge.norm();
      if (!(len > 0)) continue;
      inside = std::min(inside, edge.cross(p - p0).dot(normal) / len);
    }
    if (inside > best_inside) {
      best_inside = inside;
      best = q;
    }
  }
  return best;
}

std::vector<ElementIndex> ElementTree::leaves() const {
  std::vector<ElementIndex> out, stack;
  for (std::size_t e = 0; e < size(); ++e) {
    if (parent[e] >= 0) continue;
    stack.push_back(static_cast<ElementIndex>(e));
    while (!stack.empty()) {
      const ElementIndex x = stack.back();
      stack.pop_back();
      if (first_child[static_cast<std::size_t>(x)] < 0) {
        out.push_back(x);
        continue;
      }
      for (int q = 3; q >= 0; --q) stack.push_back(first_child[static_cast<std::size_t>(x)] + q);
    }
  }
  return out;
}

int ElementTree::depth() const {
  int d = 0;
  for (const auto l : level) d = std::max(d, static_cast<int>(l));
  return d;
}

std::size_t ElementTree::memory_bytes() const {
  return corner.capacity() * sizeof(corner[0]) + corner_count.capacity() + root.capacity() * sizeof(std::int32_t) +
         parent.capacity() * sizeof(ElementIndex) + first_child.capacity() * sizeof(ElementIndex) +
         level.capacity() * sizeof(std::int16_t) + area.capacity() * sizeof(double) +
         split_kind.capacity() * sizeof(SplitKind);
}

Vec3 element_point(const ElementTree& tree, std::size_t e, double u1, double u2) {
  const auto& c = tree.corner[e];
  const Eigen::Vector2d b = sample_uniform_triangle(u1, u2);
  if (tree.corner_count[e] == 3) return b.x() * c[0] + b.y() * c[1] + (1 - b.x() - b.y()) * c[2];
  const double a0 = (c[1] - c[0]).cross(c[2] - c[0]).norm(), a1 = (c[2] - c[0]).cross(c[3] - c[0]).norm();
  const double split = a0 + a1 > 0 ? a0 / (a0 + a1) : 1.0;
  if (u1 < split) {
    const Eigen::Vector2d bb = sample_uniform_triangle(u1 / split, u2);
    return bb.x() * c[0] + bb.y() * c[1] + (1 - bb.x() - bb.y()) * c[2];
  }
  const Eigen::Vector2d bb = sample_uniform_triangle(std::min((u1 - split) / (1 - split), 0.9999999999999999), u2);
  return bb.x() * c[0] + bb.y() * c[2] + (1 - bb.x() - bb.y()) * c[3];
}

}  // namespace radwalk
