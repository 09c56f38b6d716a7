#pragma once
// Geometric measures of one Mesh face, as validate_mesh uses them. Corners in face order; a quad is the triangle
// fan (0,1,2), (0,2,3), as in PatchSet.
#include <cstddef>

#include "core/types.h"
#include "mesh/mesh.h"

namespace radwalk {

// Area of the triangle fan: |(p1-p0) x (p2-p0)|/2 (+ |(p2-p0) x (p3-p0)|/2 for a quad).
double face_area(const Mesh& mesh, std::size_t f);

// Newell's vector area 1/2 sum_k p_k x p_(k+1); its direction is the face normal (zero for a degenerate face).
Vec3 face_vector_area(const Mesh& mesh, std::size_t f);

// Relative non-planarity of a quad: the largest distance of a corner from the plane through the corners' mean
// with the Newell normal, divided by the quad's width across its longer diagonal, w = 2 |vector area| /
// (longer diagonal). For a square (and nearly for any fat quad) w is the diagonal; for a thin quad it is its
// short extent, so a thin quad folded along its length (two halves at 90 degrees, 255 x 1 units) measures its
// fold, not the 1e-3 its diagonal would make of it. 0 for a triangle.
double quad_nonplanarity(const Mesh& mesh, std::size_t f);

// Smallest signed sine of the turning angle at a quad's corners, measured about the Newell normal:
// ((p_k - p_(k-1)) x (p_(k+1) - p_k)) . n / (|p_k - p_(k-1)| |p_(k+1) - p_k|). Negative at a reflex corner
// (concave quad) or at the corners of a bow-tie; 0 at a straight corner. 1 for a triangle.
double quad_min_turn_sine(const Mesh& mesh, std::size_t f);

// Area ambiguity of a quad (0 for a triangle): a bent quad has no one area. Its two triangulations (fans 0-2 and
// 1-3) and its bilinear surface (where its patches lie) have areas between its vector area |A_v| and the larger
// triangulation's, so the ambiguity is that spread relative to the larger: (max(A_02, A_13) - |A_v|) /
// max(A_02, A_13). A planar convex quad has 0 up to rounding; a square with a corner lifted to a non-planarity b
// about 8 b^2 (8e-4 at b = 1e-2); a thin quad far more (first order in its bend).
double quad_area_ambiguity(const Mesh& mesh, std::size_t f);

}  // namespace radwalk
