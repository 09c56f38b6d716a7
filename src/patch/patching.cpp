#include "patch/patching.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <tuple>

#include "core/error.h"
#include "mesh/edge_table.h"

namespace radwalk {

namespace {

// The points of the patch set and the lookup of shared corner and edge points.
class PointPool {
 public:
  PointPool(const Mesh& mesh, const EdgeTable& table, std::vector<Vec3>& points)
      : mesh_(mesh), table_(table), points_(points), welded_point_(table.welded_source.size(), -1) {}

  // The point of corner k of face f.
  std::int32_t corner(std::size_t f, int k) {
    const std::int32_t w = table_.weld[static_cast<std::size_t>(mesh_.faces[f][static_cast<std::size_t>(k)])];
    std::int32_t& p = welded_point_[static_cast<std::size_t>(w)];
    if (p < 0) p = add(position(w));
    return p;
  }

  // The point at step s (0..n) of n along side k of face f, walking in the face's direction (corner k -> k+1).
  std::int32_t on_side(std::size_t f, int k, int s, int n) {
    const int n_corners = mesh_.corner_count(f);
    if (s == 0) return corner(f, k);
    if (s == n) return corner(f, (k + 1) % n_corners);
    const auto e = static_cast<std::size_t>(table_.face_edge[f][static_cast<std::size_t>(k)]);
    const std::int32_t a = table_.weld[static_cast<std::size_t>(mesh_.faces[f][static_cast<std::size_t>(k)])];
    // Fraction i / n from the lower welded vertex, reduced, so every face cutting the edge there gets this point.
    // The first face cutting edge e into n parts creates its missing points in order from the lower vertex (as the
    // conforming split did, so a mesh whose faces are cut alike keeps its former point order).
    if (edge_cuts_.insert({static_cast<std::int32_t>(e), n}).second) {
      const Vec3 lo = position(table_.edges[e][0]), hi = position(table_.edges[e][1]);
      for (int i = 1; i < n; ++i) {
        const int g = std::gcd(i, n);
        const auto [it, fresh] = edge_point_.try_emplace({static_cast<std::int32_t>(e), i / g, n / g}, -1);
        if (fresh) it->second = add(lo + (static_cast<double>(i / g) / (n / g)) * (hi - lo));
      }
    }
    const int i = a == table_.edges[e][0] ? s : n - s, g = std::gcd(i, n);
    const auto it = edge_point_.find({static_cast<std::int32_t>(e), i / g, n / g});
    return it->second;
  }

  std::int32_t add(const Vec3& p) {
    points_.push_back(p);
    return static_cast<std::int32_t>(points_.size() - 1);
  }

 private:
  const Vec3& position(std::int32_t welded) const {
    return mesh_.vertices[static_cast<std::size_t>(table_.welded_source[static_cast<std::size_t>(welded)])];
  }

  const Mesh& mesh_;
  const EdgeTable& table_;
  std::vector<Vec3>& points_;
  std::vector<std::int32_t> welded_point_;
  std::map<std::tuple<std::int32_t, std::int32_t, std::int32_t>, std::int32_t> edge_point_;  // (edge, p, q)
  std::set<std::pair<std::int32_t, int>> edge_cuts_;  // (edge, n) already cut
};

// How a face is split: n_u x n_v quads, or n_u^2 triangles (n_v unused).
struct Split {
  std::int64_t nu = 1, nv = 1;
};

// Point (u, v) of the bilinear quad P0 P1 P2 P3.
Vec3 bilinear(const Vec3& P0, const Vec3& P1, const Vec3& P2, const Vec3& P3, double u, double v) {
  return (1 - u) * (1 - v) * P0 + u * (1 - v) * P1 + u * v * P2 + (1 - u) * v * P3;
}

// Area of the largest corner cell of the nu x nv grid of a quad (its largest cell when the quad is planar and
// convex: the bilinear map's Jacobian is linear in (u, v)). A cell's area is half the norm of its diagonals' cross
// product (exact for a planar quad).
double largest_corner_cell(const Vec3& P0, const Vec3& P1, const Vec3& P2, const Vec3& P3, std::int64_t nu,
                           std::int64_t nv) {
  const double du = 1.0 / static_cast<double>(nu), dv = 1.0 / static_cast<double>(nv);
  double worst = 0;
  for (const double u : {0.0, 1.0 - du})
    for (const double v : {0.0, 1.0 - dv}) {
      const Vec3 a = bilinear(P0, P1, P2, P3, u, v), b = bilinear(P0, P1, P2, P3, u + du, v);
      const Vec3 c = bilinear(P0, P1, P2, P3, u + du, v + dv), d = bilinear(P0, P1, P2, P3, u, v + dv);
      worst = std::max(worst, 0.5 * (c - a).cross(d - b).norm());
    }
  return worst;
}

// parts = ceil(length / max_edge), refused above kMaxPatchCount.
std::int64_t parts_for(const Mesh& mesh, double length, double max_edge) {
  if (!(max_edge > 0)) return 1;
  const double parts = std::ceil(length / max_edge);
  if (!(parts <= static_cast<double>(kMaxPatchCount)))
    throw InputError(locate(mesh.path, 0, -1, "max edge " + number_text(max_edge) +
                                                  " would cut an edge into more than " +
                                                  std::to_string(kMaxPatchCount) + " parts"));
  return std::max<std::int64_t>(1, static_cast<std::int64_t>(parts));
}

[[noreturn]] void refuse_count(const Mesh& mesh, const PatchingOptions& o) {
  throw InputError(locate(mesh.path, 0, -1,
                          (o.max_area > 0 ? "max area " + number_text(o.max_area) + (o.max_edge > 0 ? " and " : "")
                                          : std::string()) +
                              (o.max_edge > 0 ? "max edge " + number_text(o.max_edge) : std::string()) +
                              " would make more than " + std::to_string(kMaxPatchCount) +
                              " patches; use a larger max edge or max area"));
}

// The split of face f under the options (see patching.h).
Split split_of(const Mesh& mesh, std::size_t f, const PatchingOptions& o) {
  auto P = [&](int k) -> const Vec3& {
    return mesh.vertices[static_cast<std::size_t>(mesh.faces[f][static_cast<std::size_t>(k)])];
  };
  const auto limit = static_cast<std::int64_t>(kMaxPatchCount);
  Split s;
  if (mesh.is_quad(f)) {
    const double lu = std::max((P(1) - P(0)).norm(), (P(2) - P(3)).norm());
    const double lv = std::max((P(2) - P(1)).norm(), (P(3) - P(0)).norm());
    s.nu = parts_for(mesh, lu, o.max_edge);
    s.nv = parts_for(mesh, lv, o.max_edge);
    if (s.nu * s.nv > limit) refuse_count(mesh, o);
    if (o.max_area > 0) {
      // Start near the answer (cells of about the face's aspect, floor so as not to overshoot), then add a row or
      // column across the longer cell side until the largest cell fits.
      const double area = 0.5 * (P(2) - P(0)).cross(P(3) - P(1)).norm();
      const double cells = area / o.max_area;
      if (!(cells <= static_cast<double>(kMaxPatchCount))) refuse_count(mesh, o);
      if (lu > 0 && lv > 0) {
        s.nu = std::max(s.nu, static_cast<std::int64_t>(std::floor(std::sqrt(cells * lu / lv))));
        s.nv = std::max(s.nv, static_cast<std::int64_t>(std::floor(std::sqrt(cells * lv / lu))));
      }
      while (largest_corner_cell(P(0), P(1), P(2), P(3), s.nu, s.nv) > o.max_area) {
        if (lu / static_cast<double>(s.nu) >= lv / static_cast<double>(s.nv)) ++s.nu;
        else ++s.nv;
        if (s.nu * s.nv > limit) refuse_count(mesh, o);
      }
    }
  } else {
    const double longest = std::max({(P(1) - P(0)).norm(), (P(2) - P(1)).norm(), (P(0) - P(2)).norm()});
    s.nu = parts_for(mesh, longest, o.max_edge);
    if (o.max_area > 0) {
      const double area = 0.5 * (P(1) - P(0)).cross(P(2) - P(0)).norm();
      const double m = std::ceil(std::sqrt(area / o.max_area));
      if (!(m * m <= static_cast<double>(kMaxPatchCount))) refuse_count(mesh, o);
      s.nu = std::max(s.nu, static_cast<std::int64_t>(m));
      while (area / static_cast<double>(s.nu * s.nu) > o.max_area) ++s.nu;
    }
    if (s.nu * s.nu > limit) refuse_count(mesh, o);
  }
  return s;
}

// The mesh must have passed validate_mesh; these cheap checks only keep a skipped validation from crashing.
void check_preconditions(const Mesh& mesh, const PatchingOptions& o) {
  if (std::isnan(o.max_edge)) throw InputError(locate(mesh.path, 0, -1, "max edge is NaN"));
  if (std::isnan(o.max_area)) throw InputError(locate(mesh.path, 0, -1, "max area is NaN"));
  const auto n_vertices = static_cast<std::int64_t>(mesh.vertices.size());
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    for (int k = 0; k < mesh.corner_count(f); ++k) {
      const std::int32_t v = mesh.faces[f][static_cast<std::size_t>(k)];
      if (v < 0 || v >= n_vertices)
        throw InputError(locate(mesh.path, f < mesh.face_line.size() ? mesh.face_line[f] : 0, static_cast<long>(f),
                                "vertex index out of range (validate the mesh before patching)"));
    }
    if (f >= mesh.face_material.size() || mesh.face_material[f] < 0 ||
        static_cast<std::size_t>(mesh.face_material[f]) >= mesh.materials.size())
      throw InputError(locate(mesh.path, f < mesh.face_line.size() ? mesh.face_line[f] : 0, static_cast<long>(f),
                              "face without a valid material (validate the mesh before patching)"));
  }
}

}  // namespace

PatchSet make_patches(const Mesh& mesh, double max_edge) {
  PatchingOptions o;
  o.max_edge = max_edge;
  return make_patches(mesh, o);
}

PatchSet make_patches(const Mesh& mesh, const PatchingOptions& options) {
  check_preconditions(mesh, options);
  const EdgeTable table = build_edge_table(mesh);

  // Step 1: the split of each face and the patch count, so that an absurd bound is refused before allocating.
  std::vector<Split> split(mesh.face_count());
  std::size_t total = 0;
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    split[f] = split_of(mesh, f, options);
    total += static_cast<std::size_t>(mesh.is_quad(f) ? split[f].nu * split[f].nv : split[f].nu * split[f].nu);
    if (total > kMaxPatchCount) refuse_count(mesh, options);
  }

  PatchSet s;
  s.source = mesh.path;
  s.materials = mesh.materials;
  set_group_names(mesh, s);
  s.corners.reserve(total);
  s.face.reserve(total);
  s.material.reserve(total);
  PointPool pool(mesh, table, s.points);
  auto emit = [&](std::size_t f, std::array<std::int32_t, 4> corners) {
    s.corners.push_back(corners);
    s.face.push_back(static_cast<std::int32_t>(mesh.source_face(f)));  // the input face, also after repairs
    s.material.push_back(mesh.face_material[f]);
  };

  // Step 2: split each face; sub-patches in face order, row by row.
  std::vector<std::int32_t> grid;
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const Vec3& P0 = mesh.vertices[static_cast<std::size_t>(mesh.faces[f][0])];
    const Vec3& P1 = mesh.vertices[static_cast<std::size_t>(mesh.faces[f][1])];
    const Vec3& P2 = mesh.vertices[static_cast<std::size_t>(mesh.faces[f][2])];
    if (mesh.is_quad(f)) {
      // Quad: grid point (i, j) at u = i / nu along side 0, v = j / nv along side 3 reversed.
      const Vec3& P3 = mesh.vertices[static_cast<std::size_t>(mesh.faces[f][3])];
      const int nu = static_cast<int>(split[f].nu), nv = static_cast<int>(split[f].nv);
      grid.assign(static_cast<std::size_t>((nu + 1) * (nv + 1)), -1);
      auto at = [&](int i, int j) -> std::int32_t& { return grid[static_cast<std::size_t>(j * (nu + 1) + i)]; };
      for (int j = 0; j <= nv; ++j)
        for (int i = 0; i <= nu; ++i) {
          if (j == 0) at(i, j) = pool.on_side(f, 0, i, nu);
          else if (i == nu) at(i, j) = pool.on_side(f, 1, j, nv);
          else if (j == nv) at(i, j) = pool.on_side(f, 2, nu - i, nu);
          else if (i == 0) at(i, j) = pool.on_side(f, 3, nv - j, nv);
          else at(i, j) = pool.add(bilinear(P0, P1, P2, P3, static_cast<double>(i) / nu, static_cast<double>(j) / nv));
        }
      for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) emit(f, {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
    } else {
      // Triangle: grid point (i, j), i + j <= m, at P0 + (i/m)(P1 - P0) + (j/m)(P2 - P0).
      const int m = static_cast<int>(split[f].nu);
      grid.assign(static_cast<std::size_t>((m + 1) * (m + 1)), -1);
      auto at = [&](int i, int j) -> std::int32_t& { return grid[static_cast<std::size_t>(j * (m + 1) + i)]; };
      for (int j = 0; j <= m; ++j)
        for (int i = 0; i + j <= m; ++i) {
          if (j == 0) at(i, j) = pool.on_side(f, 0, i, m);
          else if (i + j == m) at(i, j) = pool.on_side(f, 1, j, m);
          else if (i == 0) at(i, j) = pool.on_side(f, 2, m - j, m);
          else {
            const double u = static_cast<double>(i) / m, v = static_cast<double>(j) / m;
            at(i, j) = pool.add(P0 + u * (P1 - P0) + v * (P2 - P0));
          }
        }
      for (int j = 0; j < m; ++j)
        for (int i = 0; i + j < m; ++i) {
          emit(f, {at(i, j), at(i + 1, j), at(i, j + 1), -1});
          if (i + j + 1 < m) emit(f, {at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), -1});
        }
    }
  }

  // Step 3: radiometry from the materials, then geometry.
  set_radiometry_from_materials(s);
  compute_patch_geometry(s);
  return s;
}

PatchAreaDistribution patch_area_distribution(const PatchSet& patches) {
  PatchAreaDistribution d;
  d.count = patches.size();
  if (d.count == 0) return d;
  std::vector<double> a = patches.area;
  std::sort(a.begin(), a.end());
  d.min = a.front();
  d.max = a.back();
  d.median = d.count % 2 ? a[d.count / 2] : 0.5 * (a[d.count / 2 - 1] + a[d.count / 2]);
  return d;
}

}  // namespace radwalk
