#include "patch/display_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

namespace radwalk {
namespace {

// Union-find over patches (path halving).
struct Groups {
  std::vector<std::int32_t> parent;
  explicit Groups(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  std::int32_t find(std::int32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void unite(std::int32_t a, std::int32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

bool emits(const PatchSet& p, std::size_t i) { return (p.E[i] > 0).any(); }

bool smooth_together(const PatchSet& p, std::size_t i, std::size_t j, const NeighbourOptions& o) {
  return p.material[i] == p.material[j] && emits(p, i) == emits(p, j) &&
         p.normal[i].dot(p.normal[j]) >= o.min_normal_dot;
}

// Parameter in (0, length) along edge a -> b of a point within tol of the segment's inside, or -1.
double inside_edge(const Vec3& a, const Vec3& b, const Vec3& v, double tol) {
  const Vec3 d = b - a;
  const double length = d.norm();
  if (!(length > 2 * tol)) return -1;
  const double t = (v - a).dot(d) / length;
  if (t <= tol || t >= length - tol) return -1;
  return (v - a - t * d / length).norm() <= tol ? t : -1;
}

}  // namespace

DisplayMesh make_display_mesh(const PatchSet& patches, const NeighbourOptions& options) {
  const std::size_t n = patches.size();
  DisplayMesh mesh;
  Groups groups(n);

  // Patches sharing a corner point.
  std::vector<std::vector<std::int32_t>> users(patches.points.size());
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < patches.corner_count(i); ++c) users[patches.corners[i][c]].push_back(std::int32_t(i));
  for (const auto& u : users)
    for (std::size_t a = 0; a < u.size(); ++a)
      for (std::size_t b = a + 1; b < u.size(); ++b)
        if (smooth_together(patches, u[a], u[b], options)) groups.unite(u[a], u[b]);

  // Patches touching along part of an edge (T-junctions included), and the T-junction points they leave.
  const double tol = options.relative_tolerance * patches.scene_extent();
  std::vector<std::vector<std::pair<int, double>>> inserted_edge(n);  // per patch: (edge, t)
  std::vector<std::vector<std::int32_t>> inserted_point(n);
  for (const auto& [i, j] : edge_neighbours(patches, options)) {
    if (!smooth_together(patches, i, j, options)) continue;
    groups.unite(i, j);
    for (const auto& [p, q] : {std::pair{i, j}, std::pair{j, i}}) {
      const int k = patches.corner_count(p);
      for (int c = 0; c < k; ++c)
        for (int m = 0; m < patches.corner_count(q); ++m) {
          const std::int32_t v = patches.corners[q][m];
          const double t = inside_edge(patches.corner(p, c), patches.corner(p, (c + 1) % k), patches.points[v], tol);
          if (t < 0) continue;
          bool known = false;
          for (std::size_t e = 0; e < inserted_point[p].size(); ++e) known |= inserted_point[p][e] == v;
          if (known) continue;
          inserted_edge[p].emplace_back(c, t);
          inserted_point[p].push_back(v);
        }
    }
  }

  // Groups numbered in order of their first patch.
  mesh.group.resize(n);
  std::vector<std::int32_t> number(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    const std::int32_t root = groups.find(std::int32_t(i));
    if (number[root] < 0) number[root] = std::int32_t(mesh.groups++);
    mesh.group[i] = number[root];
  }

  // Display points: one per (source point, group), in order of first use. Each source point keeps the display
  // points made of it as a chain through next_of (a point is in a few groups at most): O(1) per corner with two
  // arrays, instead of a search tree of (source, group) keys (a node allocated per display point and a cache miss
  // per level, the largest cost of the display mesh at 10^6 patches).
  std::vector<std::int64_t> first_of(patches.points.size(), -1);  // per source point: its latest display point
  std::vector<std::int64_t> next_of;         // per display point: the previous one of its source point, or -1
  std::vector<std::int32_t> group_of_point;  // per display point: its group
  const auto display_point = [&](std::int32_t source, std::int32_t group) {
    for (std::int64_t d = first_of[std::size_t(source)]; d >= 0; d = next_of[std::size_t(d)])
      if (group_of_point[std::size_t(d)] == group) return d;
    const auto d = std::int64_t(mesh.points.size());
    mesh.points.push_back(patches.points[source]);
    mesh.source_point.push_back(source);
    group_of_point.push_back(group);
    next_of.push_back(first_of[std::size_t(source)]);
    first_of[std::size_t(source)] = d;
    return d;
  };
  mesh.offsets.reserve(n + 1);
  mesh.offsets.push_back(0);
  for (std::size_t i = 0; i < n; ++i) {
    const int k = patches.corner_count(i);
    std::vector<std::size_t> order(inserted_point[i].size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return inserted_edge[i][a] < inserted_edge[i][b];
    });
    std::size_t next = 0;
    for (int c = 0; c < k; ++c) {
      mesh.ids.push_back(display_point(patches.corners[i][c], mesh.group[i]));
      for (; next < order.size() && inserted_edge[i][order[next]].first == c; ++next)
        mesh.ids.push_back(display_point(inserted_point[i][order[next]], mesh.group[i]));
    }
    mesh.offsets.push_back(std::int64_t(mesh.ids.size()));
  }
  return mesh;
}

std::vector<double> point_average(const DisplayMesh& mesh, const PatchSet& patches, const std::vector<double>& values,
                                  int components) {
  const std::size_t m = mesh.points.size();
  std::vector<double> sum(m * components, 0.0), weight(m * components, 0.0);
  for (std::size_t i = 0; i + 1 < mesh.offsets.size(); ++i)
    for (std::int64_t k = mesh.offsets[i]; k < mesh.offsets[i + 1]; ++k) {
      const auto p = std::size_t(mesh.ids[k]);
      for (int c = 0; c < components; ++c) {
        const double v = values[i * components + c];
        if (!std::isfinite(v)) continue;
        sum[p * components + c] += patches.area[i] * v;
        weight[p * components + c] += patches.area[i];
      }
    }
  for (std::size_t k = 0; k < sum.size(); ++k)
    sum[k] = weight[k] > 0 ? sum[k] / weight[k] : std::numeric_limits<double>::quiet_NaN();
  return sum;
}

}  // namespace radwalk
