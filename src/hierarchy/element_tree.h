#pragma once
// The element tree of every input patch: the root element of patch i is element i, and an element is split
// regularly into four children that tile it exactly (docs/theory/hierarchical_radiosity.md, "Elements").
//
// Splits (corners c0 .. c3 counter-clockwise about the patch normal, m_ab the midpoint of c_a c_b):
//   quad     -> (c0, m01, m, m30), (m01, c1, m12, m), (m, m12, c2, m23), (m30, m, m23, c3),
//               m = (c0 + c1 + c2 + c3) / 4, the bilinear centre; on a planar quad the lines m01-m23 and m30-m12
//               both pass through m (each's midpoint is m), so the four children tile the parent with straight
//               edges and their areas add up to the parent's up to rounding;
//   triangle -> (c0, m01, m20), (m01, c1, m12), (m20, m12, c2), (m01, m12, m20): four congruent triangles of a
//               quarter of the area, the middle one with the same orientation.
// Every child keeps its root's plane, normal, input patch, reflectance and emission. Children are appended, so a
// child's index is always above its parent's: a pass in increasing index is top-down, decreasing bottom-up.
// Corner coordinates of a midpoint are computed once per split and shared by the children that use it, and
// (a + b) / 2 is symmetric in a, b in floating point, so neighbouring elements' shared corners are bit-identical.
#include <array>
#include <cstdint>
#include <vector>

#include "core/types.h"
#include "patch/patch_set.h"

namespace radwalk {

using ElementIndex = std::int32_t;

struct ElementTree {
  std::vector<std::array<Vec3, 4>> corner;   // corner[3] unused for a triangle
  std::vector<std::int8_t> corner_count;     // 3 or 4
  std::vector<std::int32_t> root;            // the input patch (index into the PatchSet) of the element
  std::vector<ElementIndex> parent;          // -1 for a root
  std::vector<ElementIndex> first_child;     // -1 for a leaf; else the four children first_child .. first_child + 3
  std::vector<std::int16_t> level;           // 0 for a root
  std::vector<double> area;

  std::size_t size() const { return area.size(); }
  bool is_leaf(std::size_t e) const { return first_child[e] < 0; }
  // Splits leaf e into its four children (above) and returns the first child's index. e must be a leaf.
  ElementIndex split(std::size_t e);
  // The child of (non-leaf) e that contains point p of e's plane: the child whose smallest signed distance from p
  // to its edge lines (positive inside) is largest, so a point on a shared edge or slightly off the element
  // (rounding) still gets exactly one child. O(1).
  ElementIndex child_containing(std::size_t e, const Vec3& p, const Vec3& normal) const;
  // The leaves, root by root in depth-first order of the children (a deterministic order for outputs).
  std::vector<ElementIndex> leaves() const;
  // The deepest level of any element.
  int depth() const;
  // Bytes held by the arrays (capacity), for the run summary.
  std::size_t memory_bytes() const;
};

// One root element per patch (element i = patch i), no children.
ElementTree make_element_tree(const PatchSet& patches);

// Area of the polygon corners[0 .. count-1] as the PatchSet counts it (a quad as triangles (0,1,2) and (0,2,3)).
double element_area(const std::array<Vec3, 4>& corners, int count);

// A uniform point on element e from u in [0, 1)^2 (pdf 1 / area), as sample_patch_point on a patch: a quad is the
// triangles (0,1,2), (0,2,3) chosen in proportion to their areas.
Vec3 element_point(const ElementTree& tree, std::size_t e, double u1, double u2);

}  // namespace radwalk
