#include "mesh/polygon_faces.h"

#include "core/error.h"
#include "mesh/triangulate.h"

namespace radwalk {

namespace {
constexpr long kExamples = 10;  // faces named per kind of repair
}  // namespace

void PolygonFaces::note(Repairs& r, const std::string& example) {
  if (r.count++ < kExamples) r.examples += (r.examples.empty() ? "" : ", ") + example;
}

void PolygonFaces::push(const std::array<std::int32_t, 4>& corners, long line, std::int32_t material,
                        std::int32_t group, std::int32_t source) {
  mesh_.faces.push_back(corners);
  mesh_.face_line.push_back(line);
  mesh_.face_material.push_back(material);
  mesh_.face_group.push_back(group);
  mesh_.face_source.push_back(source);
}

void PolygonFaces::add(const std::vector<std::int32_t>& input, long line, std::int32_t material,
                       std::int32_t group, std::int32_t source) {
  if (input.size() <= 4) {
    std::array<std::int32_t, 4> c{-1, -1, -1, -1};
    for (std::size_t k = 0; k < input.size(); ++k) c[k] = input[k];
    push(c, line, material, group, source);
    return;
  }
  const std::string where = mesh_.context_of(material, group);  // for messages
  const std::string n = std::to_string(input.size());
  if (strict_)
    throw InputError(locate(mesh_.path, line, source, "has " + n + " vertices" + where +
                                                          "; radwalk takes triangles and quads only with --strict "
                                                          "(without it, polygons are triangulated)"));
  if (input.size() > kMaxPolygonCorners)
    throw InputError(locate(mesh_.path, line, source, "has " + n + " vertices" + where + ", more than the " +
                                                          std::to_string(kMaxPolygonCorners) +
                                                          " radwalk triangulates; split the polygon"));
  std::vector<std::int32_t> corners;
  for (std::int32_t v : input) {
    if (v < 0 || static_cast<std::size_t>(v) >= mesh_.vertices.size())
      throw InputError(locate(mesh_.path, line, source, "bad vertex index: vertex " + std::to_string(long(v) + 1) +
                                                            " (counting from 1) does not exist, the file has " +
                                                            std::to_string(mesh_.vertices.size()) + " vertices"));
    if (corners.empty() || corners.back() != v) corners.push_back(v);
  }
  if (corners.size() > 1 && corners.front() == corners.back()) corners.pop_back();
  std::vector<Vec3> points;
  for (std::int32_t v : corners) points.push_back(mesh_.vertices[static_cast<std::size_t>(v)]);
  const auto triangles = corners.size() >= 3 ? triangulate_polygon(points) : std::nullopt;
  if (!triangles) {
    Vec3 N = Vec3::Zero();
    for (std::size_t k = 0; k < points.size(); ++k) N += points[k].cross(points[(k + 1) % points.size()]);
    if (!(N.norm() > 0)) {  // no area, no power: dropped
      note(dropped_, "face " + std::to_string(source) + " (line " + std::to_string(line) + ")" + where);
      return;
    }
    throw InputError(locate(mesh_.path, line, source, "polygon with " + n + " vertices" + where +
                                                          " is self-intersecting (no ear to cut); split it into "
                                                          "simple polygons"));
  }
  for (const auto& t : *triangles)
    push({corners[static_cast<std::size_t>(t[0])], corners[static_cast<std::size_t>(t[1])],
          corners[static_cast<std::size_t>(t[2])], -1},
         line, material, group, source);
  note(triangulated_, "face " + std::to_string(source) + " (line " + std::to_string(line) + ", " + n +
                          " corners)" + where + " into " + std::to_string(triangles->size()) + " triangles");
}

void PolygonFaces::report() const {
  auto line = [&](const Repairs& r, const std::string& what) {
    if (r.count == 0) return;
    std::string more = r.count > kExamples ? " and " + std::to_string(r.count - kExamples) + " more" : "";
    mesh_.warnings.push_back(locate(mesh_.path, 0, -1, std::to_string(r.count) + " " + what + ": " + r.examples +
                                                           more + " (--strict refuses them instead)"));
  };
  line(triangulated_, "polygon(s) with more than 4 vertices triangulated");
  line(dropped_, "polygon(s) without area dropped (they carry no power)");
}

}  // namespace radwalk
