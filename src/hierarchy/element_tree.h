#pragma once
// The element tree of every input patch: the root element of patch i is element i, and an element is split into
// four children that tile it exactly, regularly or, for a quad, in bands (docs/theory/hierarchical_radiosity.md,
// "Elements" and "Band splits").
//
// Splits (corners c0 .. c3 counter-clockwise about the patch normal, m_ab the midpoint of c_a c_b):
//   regular quad -> (c0, m01, m, m30), (m01, c1, m12, m), (m, m12, c2, m23), (m30, m, m23, c3),
//               m = (c0 + c1 + c2 + c3) / 4, the bilinear centre; on a planar quad the lines m01-m23 and m30-m12
//               both pass through m (each's midpoint is m), so the four children tile the parent with straight
//               edges and their areas add up to the parent's up to rounding;
//   triangle -> (c0, m01, m20), (m01, c1, m12), (m20, m12, c2), (m01, m12, m20): four congruent triangles of a
//               quarter of the area, the middle one with the same orientation (a triangle is always split so:
//               its four children are similar to it, and no band split of a triangle into 4 tiles it with
//               triangles or quads that are all better shaped than it);
//   bands of a quad across the edge pair (c0 c1, c3 c2) (SplitKind::bands_01): with p_t = c0 + t (c1 - c0) and
//               q_t = c3 + t (c2 - c3) at t = 1/4, 1/2, 3/4 (computed as midpoints of midpoints, p_1/2 = m01,
//               p_1/4 = (c0 + m01) / 2, p_3/4 = (m01 + c1) / 2), the children (c0, p_1/4, q_1/4, c3),
//               (p_1/4, m01, m23, q_1/4), (m01, p_3/4, q_3/4, m23), (p_3/4, c1, c2, q_3/4): each child is the quad
//               between two straight cuts p_t q_t of the planar parent, so they tile it exactly; each is a quarter
//               of the parent's extent along c0 -> c1 and its whole extent along c0 -> c3 (an element four times
//               thinner in the direction of c1 - c0);
//   bands across (c1 c2, c0 c3) (SplitKind::bands_12): the same with the roles of the edges turned, cuts from
//               c0 + t (c3 - c0) to c1 + t (c2 - c1): four times thinner in the direction of c3 - c0.
// Every child keeps its root's plane, normal, input patch, reflectance and emission. Children are appended, so a
// child's index is always above its parent's: a pass in increasing index is top-down, decreasing bottom-up.
// Corner coordinates of a midpoint are computed once per split and shared by the children that use it, and
// (a + b) / 2 is symmetric in a, b in floating point, so neighbouring elements' shared corners are bit-identical;
// the band points are midpoints of midpoints, so a neighbour that splits the shared edge the same way (bands, or
// twice regularly) from either end computes the same bits.
#include <array>
#include <cstdint>
#include <vector>

#include "core/types.h"
#include "patch/patch_set.h"

namespace radwalk {

using ElementIndex = std::int32_t;

// How an element was split (above). bands_01: cuts joining edge c0 c1 to edge c3 c2; bands_12: cuts joining edge
// c0 c3 to edge c1 c2. Quads only.
enum class SplitKind : std::int8_t { regular = 0, bands_01 = 1, bands_12 = 2 };

struct ElementTree {
  std::vector<std::array<Vec3, 4>> corner;   // corner[3] unused for a triangle
  std::vector<std::int8_t> corner_count;     // 3 or 4
  std::vector<std::int32_t> root;            // the input patch (index into the PatchSet) of the element
  std::vector<ElementIndex> parent;          // -1 for a root
  std::vector<ElementIndex> first_child;     // -1 for a leaf; else the four children first_child .. first_child + 3
  std::vector<std::int16_t> level;           // 0 for a root
  std::vector<double> area;
  std::vector<SplitKind> split_kind;         // of a non-leaf: how it was split; regular for a leaf

  std::size_t size() const { return area.size(); }
  bool is_leaf(std::size_t e) const { return first_child[e] < 0; }
  // Splits leaf e into its four children (above) and returns the first child's index. e must be a leaf; a band
  // kind needs a quad.
  ElementIndex split(std::size_t e, SplitKind kind = SplitKind::regular);
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
