#pragma once
// Input faces of any corner count into the Mesh's triangles and quads, the readers' one rule for polygons.
//
// A face that names a corner twice (consecutive or not) is split at its repeats into loops that repeat none
// (repeated_corners.h: the loops keep the area as drawn); loops of fewer than 3 corners (spikes, consecutive
// repeats) are dropped, and a face of fewer than 3 corners (`f a b`, an exporter's line segment) is dropped:
// repairs, one finding per face naming the repeats and the areas kept and dropped; with `strict` refusals.
// A face with 3 or 4 corners is kept as it is (validate_mesh judges its geometry). A polygon with more corners
// is triangulated (triangulate.h: ear clipping, concave and non-planar polygons included), each triangle keeping
// the input face index (face_source), line, group and material: a repair, one finding per polygon in
// mesh.findings (finding.h). Repeated consecutive corners of a polygon are merged first. A polygon whose outline
// crosses itself is split at its crossings into simple pieces (polygon_crossings.h: the crossing points become new
// vertices, every piece faces along the polygon's dominant normal, the area kept is the lobes' areas as drawn),
// then triangulated: a repair, its finding names the crossings and the area. A polygon with no area is dropped
// (also a repair: it carries no power). With `strict` every repair is a refusal instead, as is a polygon
// that cannot be triangulated (not simple) or has a bad vertex index: an error finding, and the polygon is left
// out (validate_mesh refuses the scene once it has collected every finding).
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

 private:
  // One outline without repeated corners (3 or 4 corners kept; more triangulated as described above).
  void add_outline(const std::vector<std::int32_t>& corners, long line, std::int32_t material, std::int32_t group,
                   std::int32_t source);
  // |1/2 sum_k c_k x c_(k+1)| (Newell), 0 if a corner is out of range.
  double outline_area(const std::vector<std::int32_t>& corners) const;
  void push(const std::array<std::int32_t, 4>& corners, long line, std::int32_t material, std::int32_t group,
            std::int32_t source);

  Mesh& mesh_;
  bool strict_;
};

}  // namespace radwalk
