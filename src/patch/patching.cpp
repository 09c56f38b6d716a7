#include "patch/patching.h"

#include <cmath>
#include <numeric>

#include "core/error.h"
#include "mesh/edge_table.h"

namespace radwalk {

namespace {

// Union-find over edge indices.
class EdgeClasses {
 public:
  explicit EdgeClasses(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  std::int32_t root(std::int32_t e) {
    while (parent_[static_cast<std::size_t>(e)] != e) {
      auto& p = parent_[static_cast<std::size_t>(e)];
      p = parent_[static_cast<std::size_t>(p)];
      e = p;
    }
    return e;
  }
  void join(std::int32_t a, std::int32_t b) { parent_[static_cast<std::size_t>(root(a))] = root(b); }

 private:
  std::vector<std::int32_t> parent_;
};

// The points of the patch set and the lookup of shared corner and edge points.
class PointPool {
 public:
  PointPool(const Mesh& mesh, const EdgeTable& table, const std::vector<std::int32_t>& divisions,
            std::vector<Vec3>& points)
      : mesh_(mesh), table_(table), divisions_(divisions), points_(points),
        welded_point_(table.welded_source.size(), -1), edge_first_(table.edge_count(), -1) {}

  // The point of corner k of face f.
  std::int32_t corner(std::size_t f, int k) {
    const std::int32_t w = table_.weld[static_cast<std::size_t>(mesh_.faces[f][static_cast<std::size_t>(k)])];
    std::int32_t& p = welded_point_[static_cast<std::size_t>(w)];
    if (p < 0) p = add(position(w));
    return p;
  }

  // The point at step s (0..n) along side k of face f, walking in the face's direction (corner k -> k+1).
  std::int32_t on_side(std::size_t f, int k, int s) {
    const int n_corners = mesh_.corner_count(f);
    const auto e = static_cast<std::size_t>(table_.face_edge[f][static_cast<std::size_t>(k)]);
    const int n = divisions_[e];
    if (s == 0) return corner(f, k);
    if (s == n) return corner(f, (k + 1) % n_corners);
    // The n - 1 inner points are created once, from the lower welded vertex towards the higher one.
    if (edge_first_[e] < 0) {
      const Vec3 lo = position(table_.edges[e][0]), hi = position(table_.edges[e][1]);
      edge_first_[e] = static_cast<std::int32_t>(points_.size());
      for (int i = 1; i < n; ++i) add(lo + (static_cast<double>(i) / n) * (hi - lo));
    }
    const std::int32_t a = table_.weld[static_cast<std::size_t>(mesh_.faces[f][static_cast<std::size_t>(k)])];
    const bool forward = a == table_.edges[e][0];
    return edge_first_[e] + (forward ? s - 1 : n - s - 1);
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
  const std::vector<std::int32_t>& divisions_;
  std::vector<Vec3>& points_;
  std::vector<std::int32_t> welded_point_;
  std::vector<std::int32_t> edge_first_;
};

// Number of parts per edge: 1 without subdivision, else ceil(longest edge of its class / max_edge).
std::vector<std::int32_t> edge_divisions(const Mesh& mesh, const EdgeTable& t, double max_edge) {
  std::vector<std::int32_t> n(t.edge_count(), 1);
  if (!(max_edge > 0)) return n;
  EdgeClasses classes(t.edge_count());
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const auto& e = t.face_edge[f];
    if (mesh.is_quad(f)) {
      classes.join(e[0], e[2]);
      classes.join(e[1], e[3]);
    } else {
      classes.join(e[0], e[1]);
      classes.join(e[1], e[2]);
    }
  }
  std::vector<double> longest(t.edge_count(), 0.0);
  auto position = [&](std::int32_t w) -> const Vec3& {
    return mesh.vertices[static_cast<std::size_t>(t.welded_source[static_cast<std::size_t>(w)])];
  };
  for (std::size_t e = 0; e < t.edge_count(); ++e) {
    const double length = (position(t.edges[e][1]) - position(t.edges[e][0])).norm();
    double& l = longest[static_cast<std::size_t>(classes.root(static_cast<std::int32_t>(e)))];
    l = std::max(l, length);
  }
  for (std::size_t e = 0; e < t.edge_count(); ++e) {
    const double parts = std::ceil(longest[static_cast<std::size_t>(classes.root(static_cast<std::int32_t>(e)))] /
                                   max_edge);
    if (!(parts <= static_cast<double>(kMaxPatchCount)))
      throw InputError(locate(mesh.path, 0, -1, "max edge " + number_text(max_edge) +
                                                    " would cut an edge into more than " +
                                                    std::to_string(kMaxPatchCount) + " parts"));
    n[e] = std::max<std::int32_t>(1, static_cast<std::int32_t>(parts));
  }
  return n;
}

// The mesh must have passed validate_mesh; these cheap checks only keep a skipped validation from crashing.
void check_preconditions(const Mesh& mesh, double max_edge) {
  if (std::isnan(max_edge)) throw InputError(locate(mesh.path, 0, -1, "max edge is NaN"));
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
  check_preconditions(mesh, max_edge);
  const EdgeTable table = build_edge_table(mesh);
  const std::vector<std::int32_t> n = edge_divisions(mesh, table, max_edge);
  auto parts = [&](std::size_t f, int side) {
    return n[static_cast<std::size_t>(table.face_edge[f][static_cast<std::size_t>(side)])];
  };

  // Step 1: count the patches, so that an absurd max_edge is refused before allocating.
  std::size_t total = 0;
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    total += mesh.is_quad(f) ? static_cast<std::size_t>(parts(f, 0)) * static_cast<std::size_t>(parts(f, 1))
                             : static_cast<std::size_t>(parts(f, 0)) * static_cast<std::size_t>(parts(f, 0));
    if (total > kMaxPatchCount)
      throw InputError(locate(mesh.path, 0, -1, "max edge " + number_text(max_edge) + " would make more than " +
                                                    std::to_string(kMaxPatchCount) +
                                                    " patches; use a larger max edge"));
  }

  PatchSet s;
  s.source = mesh.path;
  s.materials = mesh.materials;
  s.corners.reserve(total);
  s.face.reserve(total);
  s.material.reserve(total);
  PointPool pool(mesh, table, n, s.points);
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
      const int nu = parts(f, 0), nv = parts(f, 1);
      grid.assign(static_cast<std::size_t>((nu + 1) * (nv + 1)), -1);
      auto at = [&](int i, int j) -> std::int32_t& { return grid[static_cast<std::size_t>(j * (nu + 1) + i)]; };
      for (int j = 0; j <= nv; ++j)
        for (int i = 0; i <= nu; ++i) {
          if (j == 0) at(i, j) = pool.on_side(f, 0, i);
          else if (i == nu) at(i, j) = pool.on_side(f, 1, j);
          else if (j == nv) at(i, j) = pool.on_side(f, 2, nu - i);
          else if (i == 0) at(i, j) = pool.on_side(f, 3, nv - j);
          else {
            const double u = static_cast<double>(i) / nu, v = static_cast<double>(j) / nv;
            at(i, j) = pool.add((1 - u) * (1 - v) * P0 + u * (1 - v) * P1 + u * v * P2 + (1 - u) * v * P3);
          }
        }
      for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) emit(f, {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
    } else {
      // Triangle: grid point (i, j), i + j <= m, at P0 + (i/m)(P1 - P0) + (j/m)(P2 - P0).
      const int m = parts(f, 0);
      grid.assign(static_cast<std::size_t>((m + 1) * (m + 1)), -1);
      auto at = [&](int i, int j) -> std::int32_t& { return grid[static_cast<std::size_t>(j * (m + 1) + i)]; };
      for (int j = 0; j <= m; ++j)
        for (int i = 0; i + j <= m; ++i) {
          if (j == 0) at(i, j) = pool.on_side(f, 0, i);
          else if (i + j == m) at(i, j) = pool.on_side(f, 1, j);
          else if (i == 0) at(i, j) = pool.on_side(f, 2, m - j);
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

}  // namespace radwalk
