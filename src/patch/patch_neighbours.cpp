#include "patch/patch_neighbours.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace radwalk {
namespace {

// An edge by reference: its end points are the positions of a PatchSet's points (12 bytes, not the 56 of two
// copied positions: at 10^7 patches the table of 4 x 10^7 edges is 0.5 GB, not 2.2).
struct EdgeRef {
  std::int32_t a, b;
  PatchIndex patch;
};

struct Edge {
  Vec3 a, b;
  PatchIndex patch;
};

Edge edge_of(const PatchSet& patches, const EdgeRef& r) {
  return {patches.points[std::size_t(r.a)], patches.points[std::size_t(r.b)], r.patch};
}

// Collinear and overlapping along more than tol.
bool overlap(const Edge& e, const Edge& f, double tol) {
  const Vec3 d = e.b - e.a;
  const double length = d.norm();
  if (!(length > tol)) return false;
  const Vec3 u = d / length;
  const Vec3 fa = f.a - e.a, fb = f.b - e.a;
  const double ta = fa.dot(u), tb = fb.dot(u);
  if ((fa - ta * u).norm() > tol || (fb - tb * u).norm() > tol) return false;
  return std::min(length, std::max(ta, tb)) - std::max(0.0, std::min(ta, tb)) > tol;
}

}  // namespace

std::vector<std::pair<PatchIndex, PatchIndex>> edge_neighbours(const PatchSet& patches,
                                                               const NeighbourOptions& options) {
  std::vector<std::pair<PatchIndex, PatchIndex>> pairs;
  std::vector<EdgeRef> edges;
  std::size_t corners = 0;
  for (std::size_t i = 0; i < patches.size(); ++i) corners += std::size_t(patches.corner_count(i));
  edges.reserve(corners);  // exactly: a growing table would hold its old and new copies at once
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const int k = patches.corner_count(i);
    for (int c = 0; c < k; ++c) edges.push_back({patches.corners[i][c], patches.corners[i][(c + 1) % k], PatchIndex(i)});
  }
  if (edges.size() < 2) return pairs;
  const double tol = options.relative_tolerance * patches.scene_extent();

  // Uniform grid: each edge goes into every cell its bounding box (grown by tol) touches. Overlapping edges share
  // a cell. Cell size: the median edge length, doubled while edges would fill too many cells (long diagonals).
  std::vector<double> lengths;
  lengths.reserve(edges.size());
  for (const EdgeRef& r : edges) {
    const Edge e = edge_of(patches, r);
    lengths.push_back((e.b - e.a).norm());
  }
  std::nth_element(lengths.begin(), lengths.begin() + std::ptrdiff_t(lengths.size() / 2), lengths.end());
  const double extent = std::max(patches.scene_extent(), 1e-300);
  double h = std::max(lengths[lengths.size() / 2], extent * 1e-5);
  std::vector<double>().swap(lengths);
  Vec3 lo = edge_of(patches, edges[0]).a;
  for (const EdgeRef& r : edges) {
    const Edge e = edge_of(patches, r);
    lo = lo.cwiseMin(e.a).cwiseMin(e.b);
  }
  lo.array() -= 2 * tol;
  const auto cells = [&](const Edge& e, double size, auto&& visit) {
    const Vec3 a = e.a.cwiseMin(e.b).array() - tol, b = e.a.cwiseMax(e.b).array() + tol;
    std::int64_t c0[3], c1[3];
    for (int d = 0; d < 3; ++d) {
      c0[d] = std::int64_t(std::floor((a[d] - lo[d]) / size));
      c1[d] = std::int64_t(std::floor((b[d] - lo[d]) / size));
    }
    for (std::int64_t x = c0[0]; x <= c1[0]; ++x)
      for (std::int64_t y = c0[1]; y <= c1[1]; ++y)
        for (std::int64_t z = c0[2]; z <= c1[2]; ++z) visit(x, y, z);
  };
  double total = 0;  // grid entries at cell size h
  for (;;) {
    total = 0;
    for (const EdgeRef& r : edges) {
      const Edge e = edge_of(patches, r);
      double count = 1;
      const Vec3 a = e.a.cwiseMin(e.b).array() - tol, b = e.a.cwiseMax(e.b).array() + tol;
      for (int d = 0; d < 3; ++d) count *= std::floor((b[d] - lo[d]) / h) - std::floor((a[d] - lo[d]) / h) + 1;
      total += count;
    }
    if (total <= 64.0 * double(edges.size()) || h >= extent) break;
    h *= 2;
  }

  // (cell key, edge) entries, sorted by cell; every pair within a cell is a candidate. Cells per axis stay below
  // 2^21 (h >= extent * 1e-5), so the key packs exactly.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> entries;
  entries.reserve(std::size_t(total));  // exactly the count above
  for (std::size_t k = 0; k < edges.size(); ++k)
    cells(edge_of(patches, edges[k]), h, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
      const std::uint64_t key = (std::uint64_t(x) << 42) | (std::uint64_t(y) << 21) | std::uint64_t(z);
      entries.emplace_back(key, std::uint32_t(k));
    });
  std::sort(entries.begin(), entries.end());
  for (std::size_t r = 0; r < entries.size();) {
    std::size_t end = r;
    while (end < entries.size() && entries[end].first == entries[r].first) ++end;
    for (std::size_t p = r; p < end; ++p)
      for (std::size_t q = p + 1; q < end; ++q) {
        const Edge e = edge_of(patches, edges[entries[p].second]);
        const Edge f = edge_of(patches, edges[entries[q].second]);
        if (e.patch == f.patch) continue;
        const auto i = std::size_t(e.patch), j = std::size_t(f.patch);
        if (patches.normal[i].dot(patches.normal[j]) < options.min_normal_dot) continue;
        // Test from the longer edge, so a short edge inside a long one is found.
        const bool e_longer = (e.b - e.a).squaredNorm() >= (f.b - f.a).squaredNorm();
        if (e_longer ? overlap(e, f, tol) : overlap(f, e, tol))
          pairs.emplace_back(std::min(e.patch, f.patch), std::max(e.patch, f.patch));
      }
    r = end;
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

}  // namespace radwalk
