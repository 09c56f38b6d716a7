#include "mesh/polygon_faces.h"

#include <algorithm>

#include "core/error.h"
#include "core/format_number.h"
#include "mesh/polygon_crossings.h"
#include "mesh/repeated_corners.h"
#include "mesh/triangulate.h"

namespace radwalk {

void PolygonFaces::push(const std::array<std::int32_t, 4>& corners, long line, std::int32_t material,
                        std::int32_t group, std::int32_t source) {
  mesh_.faces.push_back(corners);
  mesh_.face_line.push_back(line);
  mesh_.face_material.push_back(material);
  mesh_.face_group.push_back(group);
  mesh_.face_source.push_back(source);
}

double PolygonFaces::outline_area(const std::vector<std::int32_t>& corners) const {
  Vec3 N = Vec3::Zero();
  for (std::size_t k = 0; k < corners.size(); ++k) {
    const std::int32_t a = corners[k], b = corners[(k + 1) % corners.size()];
    if (a < 0 || b < 0 || static_cast<std::size_t>(a) >= mesh_.vertices.size() ||
        static_cast<std::size_t>(b) >= mesh_.vertices.size())
      return 0;
    N += mesh_.vertices[static_cast<std::size_t>(a)].cross(mesh_.vertices[static_cast<std::size_t>(b)]);
  }
  return 0.5 * N.norm();
}

void PolygonFaces::add(const std::vector<std::int32_t>& input, long line, std::int32_t material,
                       std::int32_t group, std::int32_t source) {
  auto found = [&](const char* kind, Severity severity, const std::string& message) {
    mesh_.findings.push_back(mesh_.finding_of(source, line, material, group, kind, severity, message));
  };
  const std::string n = std::to_string(input.size());
  const CornerLoops split = split_repeated_corners(input);
  if (!split.repeated) {
    if (input.size() >= 3) return add_outline(input, line, material, group, source);
    // `f a b` (an exporter's line segment) or `f a`: no area, no power.
    if (strict_)
      return found("fewer than 3 corners", Severity::error,
                   "has " + n + " corners, a face needs at least 3 (--strict refuses what would be dropped)");
    return found("face of fewer than 3 corners dropped", Severity::repair,
                 "has " + n + " corners (a line segment or a point, not a surface): dropped, area 0 (it carries no "
                 "power; --strict refuses it)");
  }
  // Repeated corners: the outline is the loops between its repeats (repeated_corners.h), which keep its area.
  std::string repeats;
  {
    std::vector<std::int32_t> seen;
    for (std::int32_t v : input) {
      if (std::find(seen.begin(), seen.end(), v) == seen.end()) {
        seen.push_back(v);
      } else if (repeats.size() < 60 && repeats.find("vertex " + std::to_string(long(v) + 1) + ",") == std::string::npos) {
        repeats += "vertex " + std::to_string(long(v) + 1) + ", ";
      }
    }
    if (repeats.size() >= 2) repeats.resize(repeats.size() - 2);
  }
  if (strict_)
    return found("repeated corners", Severity::error,
                 "face with " + n + " corners repeats " + repeats + " (--strict refuses what would be repaired)");
  const double drawn = outline_area(input);
  std::size_t kept = 0, dropped = 0;
  double kept_area = 0;
  for (const std::vector<int>& loop : split.loops) {
    std::vector<std::int32_t> corners;
    for (int k : loop) corners.push_back(input[static_cast<std::size_t>(k)]);
    if (corners.size() < 3) {
      dropped += corners.size() == 2;  // a spike; a loop of one corner is a consecutive repeat
      continue;
    }
    const double area = outline_area(corners);
    ++kept;
    kept_area += area;
    add_outline(corners, line, material, group, source);
  }
  std::string what = "face with " + n + " corners repeats " + repeats + ": ";
  if (kept == 0) {
    return found("face without area dropped", Severity::repair,
                 what + "no loop between its repeats has 3 corners, so it has no area: dropped, area " +
                     format_number(drawn) + " (--strict refuses it)");
  }
  what += kept == 1 ? "the repeats removed, kept as one face" : "split at its repeats into " + std::to_string(kept) + " faces";
  what += " of area " + format_number(kept_area) + " (as drawn " + format_number(drawn) + ")";
  if (dropped > 0) what += ", " + std::to_string(dropped) + " spike(s) without area dropped (area 0)";
  found("repeated corners removed", Severity::repair, what + " (--strict refuses it)");
}

void PolygonFaces::add_outline(const std::vector<std::int32_t>& input, long line, std::int32_t material,
                               std::int32_t group, std::int32_t source) {
  if (input.size() <= 4) {
    std::array<std::int32_t, 4> c{-1, -1, -1, -1};
    for (std::size_t k = 0; k < input.size(); ++k) c[k] = input[k];
    push(c, line, material, group, source);
    return;
  }
  const std::string n = std::to_string(input.size());
  auto found = [&](const char* kind, Severity severity, const std::string& message) {
    mesh_.findings.push_back(mesh_.finding_of(source, line, material, group, kind, severity, message));
  };
  if (strict_)
    return found("polygon of more than 4 corners", Severity::error,
                 "has " + n + " vertices; radwalk takes triangles and quads only with --strict (without it, "
                 "polygons are triangulated)");
  if (input.size() > kMaxPolygonCorners)
    return found("polygon of too many corners", Severity::error,
                 "has " + n + " vertices, more than the " + std::to_string(kMaxPolygonCorners) +
                     " radwalk triangulates; split the polygon");
  std::vector<std::int32_t> corners;
  for (std::int32_t v : input) {
    if (v < 0 || static_cast<std::size_t>(v) >= mesh_.vertices.size())
      return found("bad vertex index", Severity::error,
                   "bad vertex index: vertex " + std::to_string(long(v) + 1) +
                       " (counting from 1) does not exist, the file has " + std::to_string(mesh_.vertices.size()) +
                       " vertices");
    if (corners.empty() || corners.back() != v) corners.push_back(v);
  }
  if (corners.size() > 1 && corners.front() == corners.back()) corners.pop_back();
  std::vector<Vec3> points;
  for (std::int32_t v : corners) points.push_back(mesh_.vertices[static_cast<std::size_t>(v)]);
  // An outline that crosses itself (in its plane) is split at its crossings first (polygon_crossings.h); any other
  // is ear-clipped as it is, and if that fails (no ear: corners that touch, a figure-eight through a corner) the
  // touches are split too.
  PolygonPieces pieces = corners.size() >= 4 ? split_at_crossings(points, false) : PolygonPieces{};
  std::optional<std::vector<std::array<std::int32_t, 3>>> triangles;
  std::string why = pieces.why;  // why a crossing outline cannot be split, if it cannot
  bool off_plane = pieces.status == PolygonPieces::Status::nonplanar;
  if (pieces.status != PolygonPieces::Status::split) {
    triangles = corners.size() >= 3 ? triangulate_polygon(points) : std::nullopt;
    if (!triangles && corners.size() >= 4) {
      pieces = split_at_crossings(points, true);
      if (!pieces.why.empty()) why = pieces.why;
      off_plane = off_plane || pieces.status == PolygonPieces::Status::nonplanar;
    }
  }
  Vec3 N = Vec3::Zero();
  for (std::size_t k = 0; k < points.size(); ++k) N += points[k].cross(points[(k + 1) % points.size()]);
  // Not split: off its plane (whatever its vector area), or degenerate (overlapping edges) with an area.
  if (!triangles && pieces.status != PolygonPieces::Status::split && !why.empty() && (off_plane || N.norm() > 0))
    return found("self-intersecting polygon", Severity::error,
                 "polygon with " + n + " vertices is self-intersecting and cannot be split: " + why +
                     "; split it into simple polygons");
  if (pieces.status == PolygonPieces::Status::split) {
    triangles = triangulate_pieces(points, pieces);
    if (!triangles) {
      if (!(N.norm() > 0) && !(pieces.area > 0))
        return found("polygon without area dropped", Severity::repair,
                     "polygon with " + n + " vertices has no area: dropped (it carries no power; --strict refuses it)");
      return found("self-intersecting polygon", Severity::error,
                   "polygon with " + n + " vertices is self-intersecting and a piece between its crossings could not "
                   "be triangulated; split it into simple polygons");
    }
    // The crossing points become vertices; the pieces' indices map to the mesh's.
    std::vector<std::int32_t> index(corners.begin(), corners.end());
    for (const Vec3& p : pieces.new_points) {
      index.push_back(static_cast<std::int32_t>(mesh_.vertices.size()));
      mesh_.vertices.push_back(p);
    }
    for (const auto& t : *triangles)
      push({index[static_cast<std::size_t>(t[0])], index[static_cast<std::size_t>(t[1])],
            index[static_cast<std::size_t>(t[2])], -1},
           line, material, group, source);
    return found("self-intersecting polygon split", Severity::repair,
                 split_message("polygon with " + n + " vertices", pieces, triangles->size()) +
                     new_vertices(mesh_.vertices.size() - pieces.new_points.size(), mesh_.vertices.size()) + " (--strict refuses it)");
  }
  if (!triangles) {
    if (!(N.norm() > 0))  // no area, no power: dropped
      return found("polygon without area dropped", Severity::repair,
                   "polygon with " + n + " vertices has no area: dropped (it carries no power; --strict refuses it)");
    return found("self-intersecting polygon", Severity::error,
                 "polygon with " + n + " vertices is self-intersecting (no ear to cut); split it into simple "
                 "polygons");
  }
  for (const auto& t : *triangles)
    push({corners[static_cast<std::size_t>(t[0])], corners[static_cast<std::size_t>(t[1])],
          corners[static_cast<std::size_t>(t[2])], -1},
         line, material, group, source);
  found("polygon triangulated", Severity::repair,
        "polygon with " + n + " vertices triangulated into " + std::to_string(triangles->size()) +
            " triangles (--strict refuses it)");
}

}  // namespace radwalk
