#include "mesh/t_junctions.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "mesh/face_geometry.h"

namespace radwalk {

namespace {

// A point that may lie on a boundary edge: a boundary vertex (a T point if it does) or the midpoint of a boundary
// edge (that edge is then covered).
struct Candidate {
  Vec3 p;
  std::int32_t vertex = -1;  // welded vertex, or -1 for a midpoint
  std::int32_t edge = -1;    // the edge of a midpoint
};

struct CellKey {
  long long x, y, z;
  bool operator==(const CellKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct CellHash {
  std::size_t operator()(const CellKey& k) const {
    return std::hash<long long>()(k.x * 73856093LL ^ k.y * 19349663LL ^ k.z * 83492791LL);
  }
};

}  // namespace

BoundaryCover find_t_junctions(const Mesh& mesh, const EdgeTable& t, double rel_tolerance) {
  BoundaryCover out;
  out.covered.assign(t.edge_count(), true);
  auto point = [&](std::int32_t w) {
    return mesh.vertices[static_cast<std::size_t>(t.welded_source[static_cast<std::size_t>(w)])];
  };
  std::vector<std::int32_t> boundary;
  for (std::size_t e = 0; e < t.edge_count(); ++e)
    if (t.use_count(e) == 1) {
      boundary.push_back(static_cast<std::int32_t>(e));
      out.covered[e] = false;
    }
  out.boundary_edges = boundary.size();
  if (boundary.empty()) return out;

  std::vector<Candidate> candidates;
  std::vector<double> lengths;
  std::vector<bool> listed(t.welded_source.size(), false);
  for (const std::int32_t e : boundary) {
    const auto& ends = t.edges[static_cast<std::size_t>(e)];
    const Vec3 a = point(ends[0]), b = point(ends[1]);
    lengths.push_back((b - a).norm());
    candidates.push_back({0.5 * (a + b), -1, e});
    for (const std::int32_t w : ends)
      if (!listed[static_cast<std::size_t>(w)]) {
        listed[static_cast<std::size_t>(w)] = true;
        candidates.push_back({point(w), w, -1});
      }
  }
  std::nth_element(lengths.begin(), lengths.begin() + static_cast<long>(lengths.size() / 2), lengths.end());
  const double cell = std::max(lengths[lengths.size() / 2], 1e-300);
  auto key = [&](const Vec3& p) {
    return CellKey{static_cast<long long>(std::floor(p.x() / cell)), static_cast<long long>(std::floor(p.y() / cell)),
                   static_cast<long long>(std::floor(p.z() / cell))};
  };
  std::unordered_map<CellKey, std::vector<std::int32_t>, CellHash> grid;
  for (std::size_t c = 0; c < candidates.size(); ++c) grid[key(candidates[c].p)].push_back(static_cast<std::int32_t>(c));

  // A long edge over many cells visits at most every non-empty cell once (the grid's size bounds its work).
  for (const std::int32_t e : boundary) {
    const auto& ends = t.edges[static_cast<std::size_t>(e)];
    const Vec3 a = point(ends[0]), b = point(ends[1]);
    const Vec3 d = b - a;
    const double length2 = d.squaredNorm();
    if (!(length2 > 0)) continue;
    const double tol = rel_tolerance * std::sqrt(length2);
    auto test = [&](std::int32_t c) {
      const Candidate& q = candidates[static_cast<std::size_t>(c)];
      if (q.edge == e || q.vertex == ends[0] || q.vertex == ends[1]) return;
      const double s = (q.p - a).dot(d) / length2;
      if (!(s > rel_tolerance && s < 1 - rel_tolerance)) return;
      if (!((q.p - (a + s * d)).norm() <= tol)) return;
      out.covered[static_cast<std::size_t>(e)] = true;
      if (q.vertex >= 0)
        out.t_junctions.push_back({e, t.uses_begin(static_cast<std::size_t>(e))->face, q.vertex, s});
      else
        out.covered[static_cast<std::size_t>(q.edge)] = true;
    };
    const CellKey lo = key(a.cwiseMin(b)), hi = key(a.cwiseMax(b));
    const double cells = double(hi.x - lo.x + 1) * double(hi.y - lo.y + 1) * double(hi.z - lo.z + 1);
    if (cells > double(grid.size())) {
      for (const auto& [k, members] : grid)
        if (k.x >= lo.x && k.x <= hi.x && k.y >= lo.y && k.y <= hi.y && k.z >= lo.z && k.z <= hi.z)
          for (const std::int32_t c : members) test(c);
      continue;
    }
    for (long long x = lo.x; x <= hi.x; ++x)
      for (long long y = lo.y; y <= hi.y; ++y)
        for (long long z = lo.z; z <= hi.z; ++z) {
          const auto it = grid.find({x, y, z});
          if (it != grid.end())
            for (const std::int32_t c : it->second) test(c);
        }
  }
  std::sort(out.t_junctions.begin(), out.t_junctions.end(),
            [](const TJunction& x, const TJunction& y) { return x.edge != y.edge ? x.edge < y.edge : x.t < y.t; });
  for (const std::int32_t e : boundary) out.uncovered += !out.covered[static_cast<std::size_t>(e)];
  return out;
}

bool is_closed_shell(const Mesh& mesh) {
  if (find_t_junctions(mesh, build_edge_table(mesh)).closed()) return true;
  return encloses(mesh, enclosure_faces(mesh));
}

std::vector<std::size_t> enclosure_faces(const Mesh& mesh) {
  std::vector<std::size_t> out;
  if (mesh.faces.empty()) return out;
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t f = 0; f < mesh.face_count(); ++f)
    for (int k = 0; k < mesh.corner_count(f); ++k) {
      const Vec3& p = mesh.vertices[static_cast<std::size_t>(mesh.faces[f][static_cast<std::size_t>(k)])];
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  const double tol = 1e-9 * (hi - lo).norm();
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const Vec3 n = face_vector_area(mesh, f);
    for (int a = 0; a < 3; ++a) {
      bool on_lo = true, on_hi = true;
      for (int k = 0; k < mesh.corner_count(f); ++k) {
        const double x = mesh.vertices[static_cast<std::size_t>(mesh.faces[f][static_cast<std::size_t>(k)])][a];
        on_lo = on_lo && std::abs(x - lo[a]) <= tol;
        on_hi = on_hi && std::abs(x - hi[a]) <= tol;
      }
      if ((on_lo && n[a] > 0) || (on_hi && n[a] < 0)) {
        out.push_back(f);
        break;
      }
    }
  }
  return out;
}

bool encloses(const Mesh& mesh, const std::vector<std::size_t>& faces) {
  if (faces.empty()) return false;
  Mesh shell;
  shell.vertices = mesh.vertices;
  for (const std::size_t f : faces) shell.faces.push_back(mesh.faces[f]);  // geometry is all the cover needs
  return find_t_junctions(shell, build_edge_table(shell)).closed();
}

}  // namespace radwalk
