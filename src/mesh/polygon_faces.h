#pragma once
// Input faces of any corner count into the Mesh's triangles and quads, the readers' one rule for polygons.
//
// A face with 3 or 4 corners is kept as it is (validate_mesh judges its geometry). A polygon with more corners
// is triangulated (triangulate.h: ear clipping, concave and non-planar polygons included), each triangle keeping
// the input face index (face_source), line, group and material: a repair, reported once per kind with the first
// faces named. Repeated consecutive corners of a polygon are merged first. A polygon with no area is dropped
// (also a repair: it carries no power). With `strict` every repair is a refusal instead, as is a polygon that
// cannot be triangulated (not simple).
#include <cstdint>
#include <string>
#include <vector>

#include "mesh/mesh.h"

namespace radwalk {

class PolygonFaces {
 public:
  PolygonFaces(Mesh& mesh, bool strict) : mesh_(mesh), strict_(strict) {}
  // Adds input face `source` with the given vertex indices (0-based; out-of-range indices are refused).
  void add(const std::vector<std::int32_t>& corners, long line, std::int32_t material, std::int32_t group,
           std::int32_t source);
  // Appends the repair warnings to mesh.warnings (one line per kind of repair).
  void report() const;

 private:
  struct Repairs {
    long count = 0;
    std::string examples;  // the first faces, "face 3 (line 10) into 5 triangles, ..."
  };
  void note(Repairs& r, const std::string& example);
  void push(const std::array<std::int32_t, 4>& corners, long line, std::int32_t material, std::int32_t group,
            std::int32_t source);

  Mesh& mesh_;
  bool strict_;
  Repairs triangulated_, dropped_;
};

}  // namespace radwalk
