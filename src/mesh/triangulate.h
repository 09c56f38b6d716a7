#pragma once
// Triangulation of a polygon face (an OBJ n-gon, a non-planar or non-convex quad) by ear clipping.
//
// The corners p_0 .. p_(n-1) (a simple polygon, convex or concave, planar or not) are projected onto the plane of
// their Newell normal N = 1/2 sum_k p_k x p_(k+1) (the polygon's vector area; its direction is the face's
// orientation). Ear clipping (Meisters 1975) then repeatedly cuts off a corner i whose triangle (i-1, i, i+1)
// turns the same way as N (a convex corner) and contains no other remaining corner, until a triangle is left.
// Each triangle keeps the polygon's orientation (its normal points along N), and for a planar simple polygon the
// triangles tile it exactly: their areas add up to |N|. A non-planar polygon is split into triangles each of which
// is planar by construction.
// Among several ears the one with the best shape (largest smallest angle sine) is cut first, which avoids
// slivers on convex polygons.
//
// Cost: the ears are kept in a priority queue by shape; cutting an ear changes only its two neighbours, which are
// tested again, and an ear test looks only at the reflex (and straight) corners, the only ones that can lie in an
// ear of a simple polygon. So n corners with r of them reflex take O(n log n + n r) operations: O(n log n) for a
// convex polygon (no corner test at all), O(n^2) at worst. TriangulationCost counts them.
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/types.h"

namespace radwalk {

// The largest polygon radwalk triangulates (ear clipping is quadratic in the corner count at worst).
inline constexpr std::size_t kMaxPolygonCorners = 4096;

// In exact arithmetic a corner's ear status changes only when a neighbour is cut; when rounding hides an ear from
// that rule and no candidate is left, every corner is tested again, at most this many times.
inline constexpr std::size_t kMaxEarRescans = 8;

// What a triangulation did: ear tests (one per corner looked at) and corner-in-ear tests (the inner loop).
struct TriangulationCost {
  std::size_t ear_tests = 0;
  std::size_t blocker_tests = 0;
};

// Triangles (indices into `corners`' order: 0 .. n-1) of the polygon with the given corner positions; nothing
// when the polygon has no orientation (zero vector area) or is not simple in its projection (no ear is left).
// When `cost` is given, the operations are added to it.
std::optional<std::vector<std::array<std::int32_t, 3>>> triangulate_polygon(const std::vector<Vec3>& corners,
                                                                            TriangulationCost* cost = nullptr);

// A quad split into two triangles along the better diagonal: the one whose two triangles both turn the quad's way
// (inside a non-convex quad) and, among two such (a convex quad), the one that bends least out of plane (the
// triangles' normals agree best), ties to the shorter diagonal. Corner indices 0..3. Nothing for a quad neither
// diagonal splits into two properly oriented triangles (a bow-tie).
std::optional<std::array<std::array<std::int32_t, 3>, 2>> split_quad(const std::array<Vec3, 4>& corners);

}  // namespace radwalk
