#pragma once
// A self-intersecting polygon split at its crossings into simple pieces (the polygon_faces.h repair of a polygon
// whose outline crosses itself: a figure-eight, a bow-tie quad, a 37-gon folded over itself in its plane).
//
// The corners p_0 .. p_(n-1) are projected onto their best-fit plane (normal n: the covariance's smallest
// eigenvector, turned along the Newell vector area N when N is not zero). Every pair of edges that cross properly
// (each one's ends strictly on the two sides of the other's line) meets at a crossing point, a new vertex; with
// `touches`, a corner lying inside another edge, or two corners at the same point, is such a meeting point too.
// At each meeting point the outline is re-joined the other way (arriving along one pass, it leaves along the
// other), which is the orientation-keeping smoothing of Seifert's algorithm: the pieces (closed loops) neither
// cross themselves nor each other, and each edge stretch keeps its direction, so the pieces' signed areas add up
// to the polygon's: sum_k A_k = N.n. A figure-eight becomes its two lobes (of opposite windings). A curve that
// winds twice around a region (a pentagram drawn in one stroke: its outline and its inner pentagon) gives nested
// loops; a loop inside another winding the same way is left out, so the region is covered once (a surface has one
// layer); a loop inside another winding the other way would be a hole (winding 0): refused (status degenerate).
//
// Orientation: every piece is given the polygon's dominant orientation, that of N (for N = 0, as in a symmetric
// figure-eight, that of the piece holding the start of edge 0), reversing the lobes that wind the other way. One
// input face is one sheet with one front: a crossing outline is a slip in the corner order (two corners swapped),
// not a fold in space, so the pieces keep one common front, and a later step that orients shells (or the user)
// can turn the face as a whole; pieces facing both ways would give one face two fronts, each lobe then a flipped
// neighbour of the other's edges.
//
// The area of the split polygon is the sum of the kept pieces' absolute areas, the lobes' areas as drawn: the
// area of the region the outline winds around (not |N|, in which opposite lobes cancel and a doubly wound region
// counts twice).
//
// Refused (status nonplanar): a polygon whose corners lie farther than kCrossingPlanarity x its bounding-box
// diagonal from their plane (a crossing in projection is then not a crossing in space). Refused (status
// degenerate): more than two passes through one point, two edges overlapping along a segment, a hole.
// Cost: the edges are bucketed in a uniform grid of about n cells over the projected bounding box, and only edges
// sharing a cell are tested: O(n) for polygons whose edges are spread out, O(n^2) at worst (n <= 4096).
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/types.h"

namespace radwalk {

// The largest distance of a corner from the plane, relative to the bounding-box diagonal, for which a
// self-intersecting polygon is split (the same 1 % validate_mesh allows a quad to be off its plane).
inline constexpr double kCrossingPlanarity = 1e-2;

struct PolygonPieces {
  enum class Status { simple, split, nonplanar, degenerate };
  Status status = Status::simple;
  std::string why;                 // for nonplanar and degenerate: what was found, one line
  std::vector<Vec3> new_points;    // crossing points; point n + j is new_points[j] (corners are points 0 .. n-1)
  std::vector<std::vector<std::int32_t>> pieces;  // each a simple loop of point indices, in the dominant orientation
  std::size_t meetings = 0;        // crossings and touches split at
  std::size_t reversed = 0;        // pieces whose own winding was reversed
  std::size_t nested = 0;          // pieces left out: inside another piece winding the same way
  double area = 0;                 // sum of the pieces' absolute areas (in the plane)
};

// The simple pieces of the polygon (status split), or status simple, with no pieces, when its outline has no
// proper crossing and, with `touches`, no touch either (without `touches`, touches are split only together with
// proper crossings: a polygon whose corners only touch, a keyhole with its bridge, is left to ear clipping first).
PolygonPieces split_at_crossings(const std::vector<Vec3>& corners, bool touches);

// The pieces' triangles (ear clipping, triangulate.h), indices into the points of `pieces` (corners, then
// new_points); pieces without area (their signed area within rounding of 0) are left out. Nothing if a piece
// cannot be triangulated.
std::optional<std::vector<std::array<std::int32_t, 3>>> triangulate_pieces(const std::vector<Vec3>& corners,
                                                                           const PolygonPieces& pieces);

// The repair's message: "WHAT crosses itself: split at 1 crossing into 2 simple pieces of area 4 in all (the
// lobes' areas as drawn), 1 lobe turned to face along the polygon's dominant normal, 2 triangles".
std::string split_message(const std::string& what, const PolygonPieces& pieces, std::size_t triangles);

// "; the crossing is new vertex 11" (1-based, as the file counts; "the crossings are new vertices 11 to 15") for
// the mesh vertices [first, end) ("" if none): later findings may name them.
std::string new_vertices(std::size_t first, std::size_t end);

}  // namespace radwalk
