#include "mesh/validate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>

#include "core/error.h"
#include "core/excerpt.h"
#include "core/format_number.h"
#include "mesh/coplanar_overlaps.h"
#include "mesh/edge_table.h"
#include "mesh/face_geometry.h"
#include "mesh/polygon_crossings.h"
#include "mesh/repeated_corners.h"
#include "mesh/t_junctions.h"
#include "mesh/triangulate.h"

namespace radwalk {

namespace {

// "vertex 5" in the file's 1-based counting.
std::string vertex_name(std::int32_t v) { return "vertex " + std::to_string(static_cast<long>(v) + 1); }

std::string material_name(const Material& m) {
  std::string s = "material '" + excerpt(m.name) + "'";
  if (!m.file.empty()) {
    s += " (";
    s += m.file;
    if (m.line > 0) s += ':' + std::to_string(m.line);
    s += ')';
  }
  return s;
}

const char* kind_name(BsdfKind k) {
  switch (k) {
    case BsdfKind::diffuse: return "diffuse";
    case BsdfKind::mirror: return "mirror";
    case BsdfKind::dielectric: return "dielectric";
    case BsdfKind::conductor: return "conductor";
    case BsdfKind::microfacet: return "microfacet";
  }
  return "?";
}

// The findings of one validation, appended to mesh.findings (finding.h) in the order found.
class FindingLog {
 public:
  explicit FindingLog(Mesh& mesh) : mesh_(mesh) {}
  void add(const std::string& kind, Severity severity, std::size_t face, const std::string& what) {
    mesh_.findings.push_back(mesh_.finding(face, kind, severity, what));
    mesh_.findings.back().stage = "validate";
  }
  // A refusal of face f: collected, the scene is refused once every finding is in (validate_mesh).
  void error(const std::string& kind, std::size_t face, const std::string& what) { add(kind, Severity::error, face, what); }
  void add_global(const std::string& kind, Severity severity, const std::string& what) {
    mesh_.findings.push_back(mesh_.finding_of(-1, 0, -1, -1, kind, severity, what));
    mesh_.findings.back().stage = "validate";
  }
  long line(std::size_t face) const { return face < mesh_.face_line.size() ? mesh_.face_line[face] : 0; }
  bool errors() const {
    return std::any_of(mesh_.findings.begin(), mesh_.findings.end(),
                       [](const Finding& f) { return f.severity == Severity::error; });
  }

 private:
  Mesh& mesh_;
};

// Keeps the faces f with keep[f] (with their lines, materials, groups and input faces).
void keep_faces(Mesh& mesh, const std::vector<bool>& keep) {
  std::size_t out = 0;
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    if (!keep[f]) continue;
    mesh.faces[out] = mesh.faces[f];
    mesh.face_line[out] = mesh.face_line[f];
    mesh.face_material[out] = mesh.face_material[f];
    mesh.face_group[out] = mesh.face_group[f];
    mesh.face_source[out] = mesh.face_source[f];
    ++out;
  }
  mesh.faces.resize(out);
  mesh.face_line.resize(out);
  mesh.face_material.resize(out);
  mesh.face_group.resize(out);
  mesh.face_source.resize(out);
}

// Step: every face has 3 or 4 corners with indices in range, and finite coordinates. Faces that fail are
// reported and left out of the later steps (which need their corners).
void check_indices_and_coordinates(Mesh& mesh, FindingLog& log) {
  const auto n_vertices = static_cast<std::int64_t>(mesh.vertices.size());
  std::vector<bool> keep(mesh.face_count(), true);
  std::vector<bool> used(mesh.vertices.size(), false);
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const auto& c = mesh.faces[f];
    if (c[0] < 0 || c[1] < 0 || c[2] < 0 || c[3] < -1) {
      log.error("fewer than 3 corners", f, "has fewer than 3 valid corners");
      keep[f] = false;
      continue;
    }
    for (int k = 0; k < mesh.corner_count(f) && keep[f]; ++k) {
      const std::int32_t v = c[static_cast<std::size_t>(k)];
      if (v >= n_vertices) {
        log.error("bad vertex index", f,
                  "bad vertex index: " + vertex_name(v) + " (counting from 1) does not exist, the file has " +
                      std::to_string(n_vertices) + " vertices");
        keep[f] = false;
      } else if (!mesh.vertices[static_cast<std::size_t>(v)].allFinite()) {
        log.error("non-finite coordinate", f, vertex_name(v) + " has a non-finite coordinate (NaN or inf)");
        keep[f] = false;
        used[static_cast<std::size_t>(v)] = true;
      }
    }
  }
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    if (!used[v] && !mesh.vertices[v].allFinite())
      log.add_global("non-finite coordinate", Severity::error,
                     vertex_name(static_cast<std::int32_t>(v)) + " has a non-finite coordinate (NaN or inf)");
  if (std::find(keep.begin(), keep.end(), false) != keep.end()) keep_faces(mesh, keep);
}

// The bounding box (lowest and highest corner) of the points the faces use.
std::pair<Vec3, Vec3> corner_bounds(const Mesh& mesh) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t f = 0; f < mesh.face_count(); ++f)
    for (int k = 0; k < mesh.corner_count(f); ++k) {
      const Vec3& p = mesh.vertices[static_cast<std::size_t>(mesh.faces[f][static_cast<std::size_t>(k)])];
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  return {lo, hi};
}

// Step: the scene's size suits single-precision ray tracing (before any area is computed: with coordinates of
// 1e77 a squared length overflows to inf). The diagonal is a scaled norm, exact at 1e-100 and at 1e300.
// Returns false when the scene cannot be measured (the later steps are skipped).
bool check_extent(const Mesh& mesh, const ValidationTolerances& tol, FindingLog& log) {
  const auto [lo, hi] = corner_bounds(mesh);
  const Vec3 span = hi - lo;
  const double extent = span.allFinite() ? span.stableNorm() : std::numeric_limits<double>::infinity();
  const double reach = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
  if (!(extent <= tol.max_extent) || !(reach <= tol.max_extent)) {
    log.add_global("scene too large", Severity::error,
                   "the scene is too large for single-precision ray tracing: extent " +
                       format_number(extent) + ", largest |coordinate| " + format_number(reach) + " (limit " +
                       format_number(tol.max_extent) + " mesh units); rescale the mesh (e.g. to metres)");
    return false;
  }
  if (!(extent >= tol.min_extent)) {
    log.add_global("scene too small", Severity::error,
                   "the scene is too small for single-precision ray tracing: extent " +
                       format_number(extent) + " (limit " + format_number(tol.min_extent) +
                       " mesh units); rescale the mesh (e.g. to millimetres)");
    return false;
  }
  if (reach > tol.max_offset_ratio * extent)
    log.add_global("scene far from the origin", Severity::warning,
                   "the scene lies far from the origin: largest |coordinate| " + format_number(reach) +
                       " is " + format_number(reach / extent) + " x its extent " + format_number(extent) +
                       ", so rays (single precision) resolve only about " + format_number(reach * 6e-8) +
                       " mesh units; move the origin into the scene");
  return true;
}
// Step: repeated corners (same index, or bit-identical positions; the readers already split faces at repeated
// indices, polygon_faces.h). The outline is split at its repeats into loops (repeated_corners.h, which keeps the
// area as drawn): loops of 3 or 4 corners stay (a quad with one repeat at adjacent corners becomes a triangle),
// the rest have no area and are dropped. A repair, reported with the areas; with strict a refusal.
void repair_repeated_corners(Mesh& mesh, const ValidationTolerances& tol, FindingLog& log) {
  const std::vector<std::int32_t> weld = weld_vertices(mesh);
  std::vector<bool> keep(mesh.face_count(), true);
  const std::size_t n_faces = mesh.face_count();
  for (std::size_t f = 0; f < n_faces; ++f) {
    const auto c = mesh.faces[f];
    const int n = mesh.corner_count(f);
    std::vector<std::int32_t> ids;
    for (int k = 0; k < n; ++k) ids.push_back(weld[static_cast<std::size_t>(c[static_cast<std::size_t>(k)])]);
    const CornerLoops split = split_repeated_corners(ids);
    if (!split.repeated) continue;
    std::string what = n == 3 ? "repeated vertex: triangle" : "repeated vertex: quad";
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j)
        if (ids[static_cast<std::size_t>(i)] == ids[static_cast<std::size_t>(j)]) {
          const std::int32_t a = c[static_cast<std::size_t>(i)], b = c[static_cast<std::size_t>(j)];
          what += a == b ? " repeats " + vertex_name(a) + " (corners " + std::to_string(i) + " and " +
                               std::to_string(j) + ")"
                         : " has corners " + std::to_string(i) + " and " + std::to_string(j) + " (" +
                               vertex_name(a) + ", " + vertex_name(b) + ") at the same point";
        }
    const double drawn = face_vector_area(mesh, f).norm();
    if (tol.strict) {
      log.error("repeated vertex", f, what + " (--strict refuses what would be repaired)");
      keep[f] = false;
      continue;
    }
    std::vector<std::array<std::int32_t, 4>> loops;
    for (const std::vector<int>& loop : split.loops) {
      if (loop.size() < 3) continue;
      std::array<std::int32_t, 4> q{-1, -1, -1, -1};
      for (std::size_t k = 0; k < loop.size(); ++k) q[k] = c[static_cast<std::size_t>(loop[k])];
      loops.push_back(q);
    }
    if (loops.empty()) {
      log.add("face without area dropped", Severity::repair, f,
              what + ": no loop between its repeats has 3 corners, so it has no area: dropped, area " +
                  format_number(drawn) + " (--strict refuses it)");
      keep[f] = false;
      continue;
    }
    // One loop (the only possible one for a triangle or a quad with 3 or 4 corners left) replaces the face.
    mesh.faces[f] = loops[0];
    const double kept = face_vector_area(mesh, f).norm();
    log.add("repeated vertex repaired", Severity::repair, f,
            what + ", repaired to a " + (loops[0][3] >= 0 ? "quad" : "triangle") + " of area " +
                format_number(kept) + " (as drawn " + format_number(drawn) + "; --strict refuses it)");
  }
  if (std::find(keep.begin(), keep.end(), false) != keep.end()) keep_faces(mesh, keep);
}

// Faces f and g are a contact pair the file declares (Mesh::source_contact_pair) lying back to back: two one-sided
// faces on each other, kept as they are (not a duplicate to repair or refuse).
bool declared_contact_pair(const Mesh& mesh, std::size_t f, std::size_t g) {
  const std::int32_t pair = mesh.contact_pair(f);
  return pair >= 0 && mesh.contact_pair(g) == pair && mesh.source_face(f) != mesh.source_face(g) &&
         !(face_vector_area(mesh, f).dot(face_vector_area(mesh, g)) > 0);
}

// Step: faces with the same welded corners (duplicates). Back to back (facing away from each other: a thin part
// modelled as two faces) they become one two-sided face: the first is kept and given a two-sided copy of its
// material (same name and properties, Material::two_sided; docs/two-sided.md), the other is dropped. Facing the
// same way, the later copy is dropped (the surface is counted once). Repairs, refused with strict. A contact pair
// the file declares (declared_contact_pair: radwalk's .vtp of a scene cut along its contacts) is not a duplicate:
// both faces stay, one-sided, without a finding.
void merge_duplicate_faces(Mesh& mesh, const ValidationTolerances& tol, FindingLog& log) {
  const EdgeTable t = build_edge_table(mesh);
  std::map<std::array<std::int32_t, 4>, std::size_t> seen;
  std::vector<bool> keep(mesh.face_count(), true);
  std::map<std::int32_t, std::int32_t> two_sided_of;  // material -> its two-sided copy
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    std::array<std::int32_t, 4> key{-1, -1, -1, -1};
    const int n = mesh.corner_count(f);
    for (int k = 0; k < n; ++k)
      key[static_cast<std::size_t>(k)] = t.weld[static_cast<std::size_t>(mesh.faces[f][static_cast<std::size_t>(k)])];
    std::sort(key.begin(), key.begin() + n);
    const auto [it, added] = seen.emplace(key, f);
    if (added) continue;
    const std::size_t g = it->second;
    if (declared_contact_pair(mesh, f, g)) continue;
    const std::string other =
        "face " + std::to_string(mesh.source_face(g)) + " (line " + std::to_string(log.line(g)) + ")";
    const bool back_to_back = !(face_vector_area(mesh, f).dot(face_vector_area(mesh, g)) > 0);
    const double area = face_area(mesh, f);
    if (tol.strict) {
      log.error("duplicate face", f,
                back_to_back ? "duplicate face: same corners as " + other +
                                   " but facing the other way; back-to-back faces would be made one two-sided face "
                                   "(--strict refuses it)"
                             : "duplicate face: same corners as " + other +
                                   "; overlapping faces would be dropped (--strict refuses it)");
      keep[f] = false;
      continue;
    }
    keep[f] = false;
    if (!back_to_back) {
      log.add("duplicate face dropped", Severity::repair, f,
              "duplicate face: same corners as " + other + ", facing the same way: dropped (area " +
                  format_number(area) + ", counted once; --strict refuses it)");
      continue;
    }
    std::int32_t& m = mesh.face_material[g];
    const std::int32_t mf = mesh.face_material[f];
    std::string materials;
    if (mf != m && mf >= 0 && m >= 0)
      materials = "; its material '" + excerpt(mesh.materials[static_cast<std::size_t>(mf)].name) +
                  "' is replaced by the other side's '" + excerpt(mesh.materials[static_cast<std::size_t>(m)].name) + "'";
    if (m >= 0 && !mesh.materials[static_cast<std::size_t>(m)].two_sided) {
      auto c = two_sided_of.find(m);
      if (c == two_sided_of.end()) {
        Material copy = mesh.materials[static_cast<std::size_t>(m)];
        copy.two_sided = true;
        mesh.materials.push_back(copy);
        c = two_sided_of.emplace(m, static_cast<std::int32_t>(mesh.materials.size() - 1)).first;
      }
      m = c->second;
    }
    log.add(
        "back-to-back faces made two-sided", Severity::repair, f,
        "duplicate face: same corners as " + other +
            " but facing the other way (a thin part modelled as two faces): the pair is one two-sided face "
            "(a front and a back patch, area " +
            format_number(area) + " each)" + materials + " (--strict refuses it)");
  }
  if (std::find(keep.begin(), keep.end(), false) != keep.end()) keep_faces(mesh, keep);
}

// The bounding-box diagonal of the faces' corners (a scaled norm).
double scene_diagonal(const Mesh& mesh) {
  const auto [lo, hi] = corner_bounds(mesh);
  return (hi - lo).stableNorm();
}

// Step (a repair unless strict): faces without area are dropped (they carry no power); quads bent beyond the
// planarity limit, non-convex, or whose area is ambiguous beyond tol.area_ambiguity, are split into two triangles
// along the better diagonal (triangulate.h). A self-intersecting quad (a bow-tie) is split at its crossing into its
// two lobes (polygon_crossings.h) when it is planar; a folded one off its plane (vector area below half its area)
// along the diagonal whose two triangles, each with area, turn the Newell normal's way (split_quad: they do not
// overlap seen along it); one neither splits is left to check_face_geometry, which refuses it.
void repair_face_geometry(Mesh& mesh, const ValidationTolerances& tol, FindingLog& log) {
  if (tol.strict) return;  // check_face_geometry refuses what would be repaired here
  const double diagonal = scene_diagonal(mesh);
  const double min_area = tol.degenerate_area * diagonal * diagonal;
  Mesh out;
  bool changed = false;
  auto keep = [&](std::size_t f, const std::array<std::int32_t, 4>& corners) {
    out.faces.push_back(corners);
    out.face_line.push_back(mesh.face_line[f]);
    out.face_material.push_back(mesh.face_material[f]);
    out.face_group.push_back(mesh.face_group[f]);
    out.face_source.push_back(mesh.face_source[f]);
  };
  // A triangle of a split: kept unless it has no area (at most min_area: a split of a face two of whose corners
  // nearly coincide), which is dropped as a degenerate face is, with its own repair finding.
  auto keep_piece = [&](std::size_t f, const std::array<std::int32_t, 4>& corners, const std::string& split) {
    const Vec3& a = mesh.vertices[static_cast<std::size_t>(corners[0])];
    const double piece = 0.5 * (mesh.vertices[static_cast<std::size_t>(corners[1])] - a)
                                   .cross(mesh.vertices[static_cast<std::size_t>(corners[2])] - a)
                                   .norm();
    if (piece > min_area) {
      keep(f, corners);
      return;
    }
    log.add("zero-area face dropped", Severity::repair, f,
            "degenerate piece dropped: " + split + " left a triangle of area " + format_number(piece) +
                ", zero or below " + format_number(tol.degenerate_area) + " x (scene diagonal " +
                format_number(diagonal) + ")^2; it carries no power");
  };
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const double area = face_area(mesh, f);
    if (!(area > min_area)) {
      log.add("zero-area face dropped", Severity::repair, f,
              "degenerate face dropped: area " + format_number(area) + " is zero or below " +
                  format_number(tol.degenerate_area) + " x (scene diagonal " + format_number(diagonal) +
                  ")^2; it carries no power");
      changed = true;
      continue;
    }
    if (!mesh.is_quad(f)) {
      keep(f, mesh.faces[f]);
      continue;
    }
    const double bend = quad_nonplanarity(mesh, f), turn = quad_min_turn_sine(mesh, f);
    const double ambiguity = quad_area_ambiguity(mesh, f);
    const bool folded = !(face_vector_area(mesh, f).norm() > 0.5 * area);
    const bool bent = bend > tol.planar_error, concave = turn < -tol.convex_sine;
    const bool ambiguous = ambiguity > tol.area_ambiguity;
    std::array<Vec3, 4> p;
    for (std::size_t k = 0; k < 4; ++k) p[k] = mesh.vertices[static_cast<std::size_t>(mesh.faces[f][k])];
    const auto split = !folded && (bent || concave || ambiguous) ? split_quad(p) : std::nullopt;
    if (!split && (folded || concave)) {
      // A bow-tie: split at its crossing into its lobes (polygon_crossings.h), if it is planar.
      const std::vector<Vec3> corners(p.begin(), p.end());
      const PolygonPieces pieces = split_at_crossings(corners, true);
      const auto triangles = pieces.status == PolygonPieces::Status::split ? triangulate_pieces(corners, pieces)
                                                                           : std::nullopt;
      if (triangles) {
        std::vector<std::int32_t> index(mesh.faces[f].begin(), mesh.faces[f].end());
        for (const Vec3& x : pieces.new_points) {
          index.push_back(static_cast<std::int32_t>(mesh.vertices.size()));
          mesh.vertices.push_back(x);
        }
        for (const auto& t : *triangles)
          keep_piece(f, {index[static_cast<std::size_t>(t[0])], index[static_cast<std::size_t>(t[1])],
                         index[static_cast<std::size_t>(t[2])], -1},
                     "splitting the self-intersecting quad at its crossing");
        changed = true;
        log.add("self-intersecting polygon split", Severity::repair, f,
                split_message("quad", pieces, triangles->size()) +
                    new_vertices(mesh.vertices.size() - pieces.new_points.size(), mesh.vertices.size()) +
                    " (--strict refuses it)");
        continue;
      }
    }
    if (!split && folded) {
      // Folded off its plane (a bow-tie in some projection, not in its own plane): the diagonal whose two
      // triangles both turn the Newell normal's way (split_quad), so that seen along that normal they lie on
      // either side of the diagonal and do not overlap, each with area; its two triangles are the area as drawn.
      const auto fold = split_quad(p);
      auto triangle_area = [&](const std::array<std::int32_t, 3>& t) {
        const Vec3& a = p[static_cast<std::size_t>(t[0])];
        return 0.5 * (p[static_cast<std::size_t>(t[1])] - a).cross(p[static_cast<std::size_t>(t[2])] - a).norm();
      };
      if (fold && triangle_area((*fold)[0]) > min_area && triangle_area((*fold)[1]) > min_area) {
        for (const auto& t : *fold)
          keep(f, {mesh.faces[f][static_cast<std::size_t>(t[0])], mesh.faces[f][static_cast<std::size_t>(t[1])],
                   mesh.faces[f][static_cast<std::size_t>(t[2])], -1});
        changed = true;
        log.add("folded quad split", Severity::repair, f,
                "folded quad split into two triangles along its diagonal " +
                    std::string((*fold)[0][0] == 0 ? "0-2" : "1-3") + " (vector area " +
                    format_number(face_vector_area(mesh, f).norm()) + " below half its area " +
                    format_number(area) + ": its outline folds over itself; the triangles, of area " +
                    format_number(triangle_area((*fold)[0]) + triangle_area((*fold)[1])) +
                    ", do not overlap seen along its normal; --strict refuses it)");
        continue;
      }
    }
    // A concave quad that neither diagonal splits into two triangles turning its way (a sliver whose corners lie
    // on a line to rounding): the diagonal whose two triangles' areas add up closest to its area.
    auto pieces = split;
    if (!pieces && concave && !folded) {
      const std::array<std::array<std::int32_t, 3>, 2> d02{{{0, 1, 2}, {0, 2, 3}}}, d13{{{1, 2, 3}, {1, 3, 0}}};
      auto drawn = [&](const std::array<std::array<std::int32_t, 3>, 2>& d) {
        double a = 0;
        for (const auto& t : d)
          a += 0.5 * (p[std::size_t(t[1])] - p[std::size_t(t[0])]).cross(p[std::size_t(t[2])] - p[std::size_t(t[0])]).norm();
        return std::abs(a - area);
      };
      pieces = drawn(d02) <= drawn(d13) ? d02 : d13;
    }
    if (!pieces) {
      keep(f, mesh.faces[f]);
      continue;
    }
    const std::string diag = (*pieces)[0][0] == 0 ? "0-2" : "1-3";
    for (const auto& t : *pieces)
      keep_piece(f, {mesh.faces[f][static_cast<std::size_t>(t[0])], mesh.faces[f][static_cast<std::size_t>(t[1])],
                     mesh.faces[f][static_cast<std::size_t>(t[2])], -1},
                 "splitting the quad along its diagonal " + diag);
    changed = true;
    if (bent)
      log.add("non-planar quad split", Severity::repair, f,
              "non-planar quad split into two triangles along its diagonal " + diag + " (a corner is " +
                  format_number(100 * bend) + "% of the quad's width off its plane, limit " +
                  format_number(100 * tol.planar_error) + "%)");
    else if (concave)
      log.add("non-convex quad split", Severity::repair, f,
              "non-convex quad split into two triangles along its inner diagonal " + diag +
                  " (turning sine " + format_number(turn) + ")");
    else
      log.add("area-ambiguous quad split", Severity::repair, f,
              "bent quad split into two triangles along its diagonal " + diag +
                  ": its triangulations and its "
                  "surface differ in area by " +
                  format_number(100 * ambiguity) + "% (limit " + format_number(100 * tol.area_ambiguity) +
                  "%), although a corner is only " + format_number(100 * bend) +
                  "% of its width off its plane");
  }
  if (!changed) return;
  mesh.faces = std::move(out.faces);
  mesh.face_line = std::move(out.face_line);
  mesh.face_material = std::move(out.face_material);
  mesh.face_group = std::move(out.face_group);
  mesh.face_source = std::move(out.face_source);
}

// Step: area, planarity and convexity, relative to the scene size.
void check_face_geometry(const Mesh& mesh, const ValidationTolerances& tol, FindingLog& log) {
  const double diagonal = scene_diagonal(mesh);
  const double min_area = tol.degenerate_area * diagonal * diagonal;
  // What the message says would happen otherwise: with --strict the repair was not tried; without, this face is
  // what repair_face_geometry could not repair.
  const auto otherwise = [&](const char* repair) {
    return tol.strict ? std::string(" (refused with --strict; otherwise ") + repair + ")"
                      : std::string(" (refused: the repair could not have it ") + repair + ")";
  };
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const double area = face_area(mesh, f);
    if (!(area > min_area)) {
      log.error("degenerate face", f,
                "degenerate face: area " + format_number(area) + " is zero or below " +
                    format_number(tol.degenerate_area) + " x (scene diagonal " + format_number(diagonal) +
                    ")^2" + otherwise("dropped"));
      continue;
    }
    if (!mesh.is_quad(f)) continue;
    // A planar simple quad has |vector area| = area; a folded or self-intersecting one (a bow-tie) has less, down
    // to 0, and then no normal to measure planarity or convexity against.
    const double vector_area = face_vector_area(mesh, f).norm();
    if (!(vector_area > 0.5 * area)) {
      log.error("self-intersecting quad", f,
                "self-intersecting or folded quad: its vector area " + format_number(vector_area) +
                    " is below half its area " + format_number(area) +
                    " (a bow-tie); split it into two triangles");
      continue;
    }
    const double bend = quad_nonplanarity(mesh, f);
    if (bend > tol.planar_error) {
      log.error("non-planar quad", f,
                "non-planar quad: a corner is " + format_number(100 * bend) +
                    "% of the quad's width off its plane (limit " + format_number(100 * tol.planar_error) +
                    "%); split it into two triangles" + otherwise("split"));
      continue;
    }
    const double turn = quad_min_turn_sine(mesh, f);
    if (turn < -tol.convex_sine) {
      log.error("non-convex quad", f,
                "non-convex quad: a corner turns the wrong way (sine " + format_number(turn) +
                    "), the quad is concave; split it into two triangles" + otherwise("split"));
      continue;
    }
    const double ambiguity = quad_area_ambiguity(mesh, f);
    if (ambiguity > tol.area_ambiguity) {
      log.error("area-ambiguous quad", f,
                "bent quad: its triangulations and its surface differ in area by " +
                    format_number(100 * ambiguity) + "% (limit " + format_number(100 * tol.area_ambiguity) +
                    "%); split it into two triangles" + otherwise("split"));
      continue;
    }
    if (bend > tol.planar_clean)
      log.add("slightly non-planar quad", Severity::warning, f,
              "slightly non-planar quad: a corner is " + format_number(100 * bend) +
                  "% of the quad's width off its plane; patches treat it as flat");
  }
}

// Step: materials exist and are physical; faces without one get the default.
void check_materials(Mesh& mesh, FindingLog& log) {
  int default_material = -1;
  const auto n_materials = static_cast<std::int32_t>(mesh.materials.size());
  std::vector<bool> keep(mesh.face_count(), true);
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    std::int32_t& m = mesh.face_material[f];
    if (m >= n_materials || m < -1) {
      log.error("material index out of range", f,
                "material index " + std::to_string(m) + " out of range (" + std::to_string(n_materials) +
                    " materials)");
      keep[f] = false;
      continue;
    }
    if (m >= 0) continue;
    // Reported before the default is given, so that the finding names no material.
    log.add("face without material", Severity::repair, f,
            "face without material: given the default 'radwalk_default' (rho 0.5, no emission)");
    if (default_material < 0) {
      Material d;
      d.name = "radwalk_default";
      d.Kd = Rgb::Constant(0.5);
      default_material = static_cast<int>(mesh.materials.size());
      mesh.materials.push_back(d);
    }
    m = default_material;
  }
  if (std::find(keep.begin(), keep.end(), false) != keep.end()) keep_faces(mesh, keep);

  std::vector<long> first_face(mesh.materials.size(), -1);
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    long& first = first_face[static_cast<std::size_t>(mesh.face_material[f])];
    if (first < 0) first = static_cast<long>(f);
  }
  for (std::size_t i = 0; i < mesh.materials.size(); ++i) {
    if (first_face[i] < 0) continue;
    const auto f = static_cast<std::size_t>(first_face[i]);
    const Material& m = mesh.materials[i];
    if (m.reflectance_missing) {  // a format without materials (STL, VTK without rho): the user names the Kd
      log.error("no reflectance given", f,
                "no reflectance given: " + material_name(m) + " has none in the file; give it with --set '" +
                    printable(m.name) + ".Kd=r,g,b' (and an emitter with --set 'NAME.Ke=r,g,b')");
      continue;
    }
    if (!((m.Kd >= 0).all() && (m.Kd < 1).all()))
      log.error("reflectance out of range", f,
                "reflectance out of range: " + material_name(m) + " has Kd " + format_rgb(m.Kd) +
                    ", rho must be in [0, 1) for the radiosity equation to have a solution" +
                    (m.texture.empty() ? std::string() : " (Kd times its texture's mean colour)") +
                    "; --set '" + excerpt(m.name) + ".Kd=r,g,b' sets it" +
                    ((m.Kd >= 0).all()
                         ? ", --rho-scale S (< " + format_number(1 / m.Kd.maxCoeff()) + ") scales every Kd"
                         : std::string()));
    if (!m.Ke.allFinite() || (m.Ke < 0).any())
      log.error("negative emission", f,
                "negative emission: " + material_name(m) + " has Ke " + format_rgb(m.Ke) +
                    ", emitted radiance must be finite and >= 0; --set '" + excerpt(m.name) +
                    ".Ke=r,g,b' sets it");
    // E = pi Ke must be finite too, and leave room for the radiosity it drives (found by fuzz_validate_patch:
    // Ke 1e308 passed and made E infinite).
    else if (!(m.Ke.maxCoeff() <= kMaxKe))
      log.error("emission too large", f,
                "emission too large: " + material_name(m) + " has Ke " + format_rgb(m.Ke) +
                    ", above the 1e300 radwalk computes with (E = pi Ke would overflow); --set '" +
                    excerpt(m.name) + ".Ke=r,g,b' sets it");
    if (m.kind != BsdfKind::diffuse)
      log.add("non-diffuse material", Severity::warning, f,
              material_name(m) + " is " + kind_name(m.kind) +
                  ": the radiosity solvers treat it as diffuse with rho = Kd (only the path tracer uses its kind)");
  }
}

// Step: orientation of the shells (orient_shells.h), reported as one warning for the flips (count, area, objects),
// a note per open shell, a warning per non-orientable shell. A mesh as_written (radwalk's own .vtp or .obj) keeps
// its orientation and sides under the defaults (orientation not given as none, auto as one-sided: the back cells
// or `radwalk_two_sided` materials the file holds already made its two-sided faces); an orientation asked for
// (orient_given, --orient outward or consistent) and --open-shells two-sided still apply, the former with a note.
void orient_faces(Mesh& mesh, const ValidationTolerances& given, FindingLog& log) {
  // A run's patches as radwalk wrote them (Mesh::as_written) are oriented and sided as that run made them: the
  // defaults keep them (the cut pieces under a footprint would otherwise close the shells of the objects standing
  // there and turn them). A user who names an orientation gets it, told that it re-derives the run's.
  ValidationTolerances tol = given;
  if (mesh.as_written && !tol.orient_given) tol.orient = OrientMode::none;
  if (mesh.as_written && tol.open_shells == OpenShellSides::automatic) tol.open_shells = OpenShellSides::one_sided;
  if (mesh.as_written && tol.orient != OrientMode::none)
    log.add_global("faces as written oriented again", Severity::note,
                   "the faces are a run's patches as radwalk wrote them, oriented by that run; --orient " +
                       std::string(orient_mode_name(tol.orient)) +
                       " orients them again (leave --orient out, or give none, to keep them as written)");
  const OrientationResult r = orient_shells(mesh, tol.orient);
  auto where = [&](std::size_t f) {
    const std::int32_t g = mesh.face_group[f];
    if (g < 0) return std::string("(no object or group)");
    const auto k = static_cast<std::size_t>(g);
    if (k < mesh.group_object.size() && !mesh.group_object[k].empty())
      return "object '" + excerpt(mesh.group_object[k]) + "'";
    return k < mesh.groups.size() ? mesh.groups[k] : std::string("(no object or group)");
  };
  if (r.flipped_faces > 0) {
    std::map<std::string, std::size_t> by;
    std::vector<std::string> order;
    for (std::size_t f : r.flipped)
      if (by[where(f)]++ == 0) order.push_back(where(f));
    std::stable_sort(order.begin(), order.end(), [&](const std::string& a, const std::string& b) { return by[a] > by[b]; });
    std::string objects;
    for (std::size_t k = 0; k < order.size() && k < 5; ++k)
      objects += (k ? ", " : "") + order[k] + " " + std::to_string(by[order[k]]);
    if (order.size() > 5) objects += ", and " + std::to_string(order.size() - 5) + " more";
    log.add_global(
        "faces flipped", Severity::warning,
        std::to_string(r.flipped_faces) + " faces (area " + format_number(r.flipped_area) +
            ") flipped by --orient " + orient_mode_name(tol.orient) + " to agree with their neighbours" +
            (tol.orient == OrientMode::outward ? " and to face out of their closed shells (the room's in)"
                                               : "") +
            ": " + objects + " (" + std::to_string(r.shells) + " shells, " + std::to_string(r.closed_shells) +
            " closed, " + std::to_string(r.rooms) +
            " enclosing the scene and facing in; --orient none keeps the file's orientation)");
  }
  const bool two_sided = tol.open_shells == OpenShellSides::two_sided ||
                         (tol.open_shells == OpenShellSides::automatic && r.enclosing_shells > 0);
  if (two_sided && !r.open_shell_faces.empty()) {
    std::map<std::int32_t, std::int32_t> two_sided_of;  // material -> its two-sided copy
    for (std::size_t f : r.open_shell_faces) {
      std::int32_t& m = mesh.face_material[f];
      if (m < 0 || mesh.materials[static_cast<std::size_t>(m)].two_sided) continue;
      auto c = two_sided_of.find(m);
      if (c == two_sided_of.end()) {
        Material copy = mesh.materials[static_cast<std::size_t>(m)];
        copy.two_sided = true;
        mesh.materials.push_back(copy);
        c = two_sided_of.emplace(m, static_cast<std::int32_t>(mesh.materials.size() - 1)).first;
      }
      m = c->second;
    }
    log.add_global("open shells made two-sided", Severity::warning,
                   std::to_string(r.open_shell_faces.size()) + " faces of " + std::to_string(r.open_shells.size()) +
                       " open shells made two-sided (--open-shells " + open_shell_sides_name(tol.open_shells) +
                       (tol.open_shells == OpenShellSides::automatic
                            ? ": in a closed room, where the light reaches their backs"
                            : "") +
                       "): each a front and a back patch; --open-shells one-sided keeps them one-sided");
    return;
  }
  for (const OpenShell& o : r.open_shells)
    log.add("open shell", Severity::note, o.first_face,
            "open shell: " + std::to_string(o.faces) + " faces (area " + format_number(o.area) + ") with " +
                std::to_string(o.boundary_edges) +
                " boundary edges; the backs of one-sided faces absorb the light that reaches them, so make "
                "an open or "
                "thin part two-sided (--open-shells two-sided, 'radwalk_two_sided 1' in its material, or "
                "--two-sided) "
                "unless its backs are hidden");
  for (std::size_t f : r.non_orientable_faces)
    log.add("non-orientable shell", Severity::warning, f,
            "non-orientable shell: its faces cannot all agree across their shared edges (a Moebius strip or faces "
            "folded through each other); some neighbours keep disagreeing");
}

// Step: duplicates, coplanar overlapping faces, non-manifold edges and vertices, orientation of neighbours,
// T-junctions (t_junctions.h).
void check_topology(const Mesh& mesh, FindingLog& log) {
  const EdgeTable t = build_edge_table(mesh);
  auto welded = [&](std::size_t f, int k) {
    return t.weld[static_cast<std::size_t>(mesh.faces[f][static_cast<std::size_t>(k)])];
  };
  auto welded_name = [&](std::int32_t w) { return vertex_name(t.welded_source[static_cast<std::size_t>(w)]); };

  // Duplicate faces: the same set of welded corners.
  std::map<std::array<std::int32_t, 4>, std::size_t> seen;
  std::vector<bool> duplicate(mesh.face_count(), false);
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    std::array<std::int32_t, 4> key{-1, -1, -1, -1};
    const int n = mesh.corner_count(f);
    for (int k = 0; k < n; ++k) key[static_cast<std::size_t>(k)] = welded(f, k);
    std::sort(key.begin(), key.begin() + n);
    const auto [it, added] = seen.emplace(key, f);
    if (added) continue;
    const std::size_t g = it->second;
    duplicate[f] = true;
    if (declared_contact_pair(mesh, f, g)) continue;  // two one-sided faces on each other, as the file declares
    const std::string other = "face " + std::to_string(mesh.source_face(g)) + " (line " + std::to_string(log.line(g)) + ")";
    if (face_vector_area(mesh, f).dot(face_vector_area(mesh, g)) > 0)
      log.error("duplicate face", f, "duplicate face: same corners as " + other + "; overlapping faces are refused");
    else
      log.error("duplicate face", f,
                "duplicate face: same corners as " + other +
                    " but facing the other way; back-to-back faces are refused (give the wall a thickness)");
  }

  // Coplanar faces that overlap facing the same way (coplanar_overlaps.h); a duplicate is reported as such. Back
  // to back they are a contact (a block's bottom on a floor), which patching cuts along (patch/contact.h).
  for (const CoplanarOverlap& o : find_coplanar_overlaps(mesh, &duplicate)) {
    if (!o.same_side) continue;
    const auto f = static_cast<std::size_t>(o.face_a), g = static_cast<std::size_t>(o.face_b);
    const std::string other =
        "face " + std::to_string(mesh.source_face(g)) + " at line " + std::to_string(log.line(g)) + mesh.context(g);
    log.add("coplanar overlapping faces", Severity::warning, f,
            "coplanar overlapping faces: this face and " + other + " lie in one plane and overlap in area " +
                format_number(o.area) + ", facing the same way" +
                "; the radiosity counts the shared area twice (remove one, or give them a gap)");
  }

  // Edges: non-manifold (3+ uses) and inconsistent orientation (2 uses in the same direction).
  for (std::size_t e = 0; e < t.edge_count(); ++e) {
    const std::string edge = "edge " + welded_name(t.edges[e][0]) + " - " + welded_name(t.edges[e][1]);
    const EdgeUse* u = t.uses_begin(e);
    if (t.use_count(e) >= 3) {
      std::string faces;
      for (const EdgeUse* x = u; x != t.uses_end(e); ++x) faces += (x == u ? "" : ", ") + std::to_string(mesh.source_face(static_cast<std::size_t>(x->face)));
      log.add("non-manifold edge", Severity::warning, static_cast<std::size_t>(u->face),
              "non-manifold edge: " + edge + " is shared by " + std::to_string(t.use_count(e)) + " faces (" + faces +
                  "); legal for radiosity, but check the model");
    } else if (t.use_count(e) == 2 && u[0].forward == u[1].forward &&
               !duplicate[static_cast<std::size_t>(u[1].face)]) {  // a duplicate is reported as such
      const auto g = static_cast<std::size_t>(u[1].face);
      log.add("flipped face", Severity::warning, g,
              "flipped face: face " + std::to_string(mesh.source_face(g)) + " and face " +
                  std::to_string(mesh.source_face(static_cast<std::size_t>(u[0].face))) + " (line " +
                  std::to_string(log.line(static_cast<std::size_t>(u[0].face))) + ") run their shared " + edge +
                  " the same way, so their normals disagree; legal for radiosity, but check the model");
    }
  }

  // T-junctions: named at the T point, a note (harmless for constant radiosity).
  const BoundaryCover cover = find_t_junctions(mesh, t);
  for (const TJunction& j : cover.t_junctions) {
    const auto& ends = t.edges[static_cast<std::size_t>(j.edge)];
    log.add("T-junction", Severity::note, static_cast<std::size_t>(j.face),
            "T-junction: " + welded_name(j.vertex) + " lies on this face's edge " + welded_name(ends[0]) + " - " +
                welded_name(ends[1]) + " without being its corner; harmless for the constant-radiosity solve (B per "
                "patch), it only matters for the smooth point fields, which the .vtp's display mesh stitches there");
  }
  // At an end a of a boundary edge a - b holding T points, the edge a - v to the nearest T point v continues it:
  // the faces using the two are joined into one fan at a (a T-junction is not a non-manifold vertex).
  std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> continues;  // (vertex, edge a - v) -> edge a - b
  {
    std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> edge_of;
    for (std::size_t e = 0; e < t.edge_count(); ++e) edge_of[{t.edges[e][0], t.edges[e][1]}] = static_cast<std::int32_t>(e);
    auto find_edge = [&](std::int32_t a, std::int32_t b) {
      const auto it = edge_of.find({std::min(a, b), std::max(a, b)});
      return it == edge_of.end() ? -1 : it->second;
    };
    for (std::size_t k = 0; k < cover.t_junctions.size(); ++k) {
      const TJunction& j = cover.t_junctions[k];
      const auto& ends = t.edges[static_cast<std::size_t>(j.edge)];
      const bool first = k == 0 || cover.t_junctions[k - 1].edge != j.edge;
      const bool last = k + 1 == cover.t_junctions.size() || cover.t_junctions[k + 1].edge != j.edge;
      if (first) {
        const std::int32_t e = find_edge(ends[0], j.vertex);
        if (e >= 0) continues[{ends[0], e}] = j.edge;
      }
      if (last) {
        const std::int32_t e = find_edge(ends[1], j.vertex);
        if (e >= 0) continues[{ends[1], e}] = j.edge;
      }
    }
  }

  // Vertices: the faces around a vertex, joined across the edges at it, must form one fan.
  const std::size_t n_welded = t.welded_source.size();
  std::vector<std::int32_t> offset(n_welded + 1, 0);
  for (std::size_t f = 0; f < mesh.face_count(); ++f)
    for (int k = 0; k < mesh.corner_count(f); ++k) ++offset[static_cast<std::size_t>(welded(f, k)) + 1];
  std::partial_sum(offset.begin(), offset.end(), offset.begin());
  std::vector<std::pair<std::int32_t, std::int8_t>> around(static_cast<std::size_t>(offset.back()));
  {
    std::vector<std::int32_t> next(offset.begin(), offset.end() - 1);
    for (std::size_t f = 0; f < mesh.face_count(); ++f)
      for (int k = 0; k < mesh.corner_count(f); ++k)
        around[static_cast<std::size_t>(next[static_cast<std::size_t>(welded(f, k))]++)] = {
            static_cast<std::int32_t>(f), static_cast<std::int8_t>(k)};
  }
  std::vector<int> parent;
  std::map<std::int32_t, int> local_of_edge;
  for (std::size_t v = 0; v < n_welded; ++v) {
    const int begin = offset[v], count = offset[v + 1] - offset[v];
    if (count < 2) continue;
    parent.resize(static_cast<std::size_t>(count));
    std::iota(parent.begin(), parent.end(), 0);
    auto root = [&](int i) {
      while (parent[static_cast<std::size_t>(i)] != i) i = parent[static_cast<std::size_t>(i)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
      return i;
    };
    local_of_edge.clear();
    int fans = count;
    for (int i = 0; i < count; ++i) {
      const auto [f, k] = around[static_cast<std::size_t>(begin + i)];
      const int n = mesh.corner_count(static_cast<std::size_t>(f));
      for (const int side : {static_cast<int>(k), (k + n - 1) % n}) {
        std::int32_t e = t.face_edge[static_cast<std::size_t>(f)][static_cast<std::size_t>(side)];
        if (!continues.empty()) {
          const auto c = continues.find({static_cast<std::int32_t>(v), e});
          if (c != continues.end()) e = c->second;
        }
        const auto [it, added] = local_of_edge.emplace(e, i);
        if (added) continue;
        const int a = root(i), b = root(it->second);
        if (a != b) {
          parent[static_cast<std::size_t>(a)] = b;
          --fans;
        }
      }
    }
    if (fans > 1)
      log.add("non-manifold vertex", Severity::warning,
              static_cast<std::size_t>(around[static_cast<std::size_t>(begin)].first),
              "non-manifold vertex: " + welded_name(static_cast<std::int32_t>(v)) + " joins " + std::to_string(fans) +
                  " fans of faces that touch only there; legal for radiosity, but check the model");
  }
}

}  // namespace

const char* open_shell_sides_name(OpenShellSides sides) {
  switch (sides) {
    case OpenShellSides::automatic: return "auto";
    case OpenShellSides::one_sided: return "one-sided";
    case OpenShellSides::two_sided: return "two-sided";
  }
  return "?";
}

OpenShellSides parse_open_shell_sides(const std::string& name) {
  if (name == "auto") return OpenShellSides::automatic;
  if (name == "one-sided") return OpenShellSides::one_sided;
  if (name == "two-sided") return OpenShellSides::two_sided;
  throw InputError("--open-shells: '" + name + "' is not one of auto, one-sided, two-sided");
}

std::vector<std::string> validation_lines(const std::vector<Finding>& findings, std::size_t per_kind) {
  return grouped_lines(findings, {Severity::repair, Severity::warning}, per_kind);
}

std::vector<std::string> validation_notes(const std::vector<Finding>& findings, std::size_t per_kind) {
  return grouped_lines(findings, {Severity::note}, per_kind);
}

void validate_mesh(Mesh& mesh, const ValidationTolerances& tolerances) {
  // Lines a reader wrote directly into mesh.warnings become findings. A second validation starts again from
  // the reader's findings (validation is idempotent).
  {
    const std::vector<std::string> generated =
        validation_lines(mesh.findings, static_cast<std::size_t>(tolerances.max_warnings_per_kind));
    mesh.findings.erase(std::remove_if(mesh.findings.begin(), mesh.findings.end(),
                                       [](const Finding& f) { return f.stage == "validate"; }),
                        mesh.findings.end());
    for (const std::string& w : mesh.warnings)
      if (std::find(generated.begin(), generated.end(), w) == generated.end()) {
        Finding f;
        f.kind = "reader notice";
        f.file = mesh.path;
        f.message = w;
        mesh.findings.push_back(f);
      }
  }
  mesh.face_material.resize(mesh.face_count(), -1);
  mesh.face_line.resize(mesh.face_count(), 0);
  mesh.face_group.resize(mesh.face_count(), -1);
  if (mesh.face_source.size() != mesh.face_count()) {
    mesh.face_source.resize(mesh.face_count());
    for (std::size_t f = 0; f < mesh.face_count(); ++f) mesh.face_source[f] = static_cast<std::int32_t>(f);
  }
  FindingLog log(mesh);

  if (mesh.faces.empty() && !log.errors()) log.add_global("no faces", Severity::error, "the scene has no faces");
  check_indices_and_coordinates(mesh, log);
  if (!mesh.faces.empty() && check_extent(mesh, tolerances, log)) {
    repair_repeated_corners(mesh, tolerances, log);
    if (!mesh.faces.empty()) repair_face_geometry(mesh, tolerances, log);
    if (mesh.faces.empty() && !log.errors())
      log.add_global("no faces with area", Severity::error, "the scene has no faces with area");
    check_face_geometry(mesh, tolerances, log);
    check_materials(mesh, log);
    if (!mesh.faces.empty()) merge_duplicate_faces(mesh, tolerances, log);
    if (!mesh.faces.empty()) orient_faces(mesh, tolerances, log);
    check_topology(mesh, log);

    // Step: an emitter (form factors need none, but a radiosity solution would be zero).
    bool emitter = false;
    for (std::size_t f = 0; f < mesh.face_count() && !emitter; ++f)
      emitter = (mesh.materials[static_cast<std::size_t>(mesh.face_material[f])].Ke > 0).any();
    if (!emitter)
      log.add_global("no emitter", Severity::warning,
                     "no emitter: no face has Ke > 0 (fine for form factors; every radiosity would be 0)");
  }
  mesh.warnings = validation_lines(mesh.findings, static_cast<std::size_t>(tolerances.max_warnings_per_kind));
  if (log.errors()) throw MeshRefused(mesh.findings);
}

}  // namespace radwalk
