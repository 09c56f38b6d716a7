#include "mesh/edge_table.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <numeric>
#include <unordered_map>

namespace radwalk {

namespace {

struct PositionKey {
  std::uint64_t x, y, z;
  auto operator<=>(const PositionKey&) const = default;
};

PositionKey key_of(const Vec3& p) {
  // Adding 0.0 maps -0.0 to +0.0 so that both weld.
  return {std::bit_cast<std::uint64_t>(p.x() + 0.0), std::bit_cast<std::uint64_t>(p.y() + 0.0),
          std::bit_cast<std::uint64_t>(p.z() + 0.0)};
}

}  // namespace

std::vector<std::int32_t> weld_vertices(const Mesh& mesh, std::int32_t* welded_count) {
  // By sorting, not hashing: O(n log n) whatever the coordinates (crafted bit patterns made a position hash
  // collide on every vertex, which took quadratic time). Vertices in order of their key, equal keys in index
  // order; the first (smallest) index of each run of equal keys represents the run.
  const std::size_t n = mesh.vertices.size();
  std::vector<PositionKey> key(n);
  for (std::size_t v = 0; v < n; ++v) key[v] = key_of(mesh.vertices[v]);
  std::vector<std::int32_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) {
    return key[static_cast<std::size_t>(a)] < key[static_cast<std::size_t>(b)];
  });
  std::vector<std::int32_t> representative(n);
  for (std::size_t r = 0; r < n; ++r) {
    const bool starts_run = r == 0 || key[static_cast<std::size_t>(order[r])] != key[static_cast<std::size_t>(order[r - 1])];
    representative[static_cast<std::size_t>(order[r])] = starts_run ? order[r] : representative[static_cast<std::size_t>(order[r - 1])];
  }
  // Welded ids in order of first appearance (a representative comes before the rest of its run).
  std::vector<std::int32_t> weld(n);
  std::int32_t next = 0;
  for (std::size_t v = 0; v < n; ++v) {
    const auto rep = static_cast<std::size_t>(representative[v]);
    weld[v] = rep == v ? next++ : weld[rep];
  }
  if (welded_count) *welded_count = next;
  return weld;
}

EdgeTable build_edge_table(const Mesh& mesh) {
  EdgeTable t;
  std::int32_t n_welded = 0;
  t.weld = weld_vertices(mesh, &n_welded);
  t.welded_source.assign(static_cast<std::size_t>(n_welded), -1);
  for (std::size_t v = t.weld.size(); v-- > 0;) t.welded_source[static_cast<std::size_t>(t.weld[v])] =
      static_cast<std::int32_t>(v);

  // Step 1: number the edges in order of first use and record each face side's edge.
  std::unordered_map<std::uint64_t, std::int32_t> edge_of;
  const std::size_t n_faces = mesh.face_count();
  t.face_edge.assign(n_faces, {-1, -1, -1, -1});
  std::vector<std::int32_t> count;
  for (std::size_t f = 0; f < n_faces; ++f) {
    const int n = mesh.corner_count(f);
    for (int k = 0; k < n; ++k) {
      const std::int32_t a = t.weld[static_cast<std::size_t>(mesh.faces[f][static_cast<std::size_t>(k)])];
      const std::int32_t b = t.weld[static_cast<std::size_t>(mesh.faces[f][static_cast<std::size_t>((k + 1) % n)])];
      const std::int32_t lo = std::min(a, b), hi = std::max(a, b);
      const std::uint64_t key = (static_cast<std::uint64_t>(static_cast<std::uint32_t>(lo)) << 32) |
                                static_cast<std::uint32_t>(hi);
      const auto [it, added] = edge_of.emplace(key, static_cast<std::int32_t>(t.edges.size()));
      if (added) {
        t.edges.push_back({lo, hi});
        count.push_back(0);
      }
      t.face_edge[f][static_cast<std::size_t>(k)] = it->second;
      ++count[static_cast<std::size_t>(it->second)];
    }
  }

  // Step 2: group the uses by edge (counting sort keeps face order within an edge).
  t.use_offset.assign(t.edges.size() + 1, 0);
  for (std::size_t e = 0; e < t.edges.size(); ++e) t.use_offset[e + 1] = t.use_offset[e] + count[e];
  t.uses.resize(static_cast<std::size_t>(t.use_offset.back()));
  std::vector<std::int32_t> next(t.use_offset.begin(), t.use_offset.end() - 1);
  for (std::size_t f = 0; f < n_faces; ++f) {
    const int n = mesh.corner_count(f);
    for (int k = 0; k < n; ++k) {
      const auto e = static_cast<std::size_t>(t.face_edge[f][static_cast<std::size_t>(k)]);
      const std::int32_t a = t.weld[static_cast<std::size_t>(mesh.faces[f][static_cast<std::size_t>(k)])];
      t.uses[static_cast<std::size_t>(next[e]++)] = {static_cast<std::int32_t>(f), static_cast<std::int8_t>(k),
                                                     a == t.edges[e][0]};
    }
  }
  return t;
}

}  // namespace radwalk
