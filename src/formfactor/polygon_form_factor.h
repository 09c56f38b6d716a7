#pragma once
// The exact unoccluded form factor between two planar polygons by contour integration (derivation, the singular
// cases and their treatment in docs/theory/polygon_form_factor.md):
//   A_P F_PQ = int_P int_Q cos(t_x) cos(t_y) / (pi r^2) dA_y dA_x
//            = (1 / 2 pi) sum_{edges e of P} sum_{edges f of Q} (u_e . u_f) int_e int_f ln r ds dt,
// Stokes' theorem applied to both area integrals (u_e, u_f unit edge directions, each contour counter-clockwise
// about its polygon's normal, r = |x(s) - y(t)|). It holds where the integrand's cosines are both >= 0, so each
// polygon is first clipped to the closed half space in front of the other's plane (Sutherland-Hodgman); the
// emitting side: only the front of each polygon counts (the clipped polygons are empty, F = 0, otherwise).
// Per edge pair:
//   - parallel edges (u_f = sigma u_e, sigma = +-1), including collinear ones that share an edge or overlap: the
//     closed form by a second antiderivative of ln sqrt(w^2 + h^2), exact (the log terms of a shared edge included);
//   - other edges: the inner integral over f in closed form, the outer over e by Gauss-Legendre quadrature,
//     composite and geometrically graded towards the point of e nearest to f where that point is closer to f than
//     e's length (edges that share a corner, or meet), so the integrable r ln r singularity costs no accuracy
//     (relative error about 1e-14).
// Far pairs (far_field_rule below) wholly in front of each other: a product Gauss rule of the point-to-point
// kernel instead (the contour terms of order L^2 ln r cancel to a sum of order L^4 / r^2, losing (r / L)^4 eps).
// Coplanar polygons facing the same way see each other at F = 0: every corner of each lies on the other's plane,
// so the clip leaves nothing strictly in front and the result is 0.
// Cost: O(corners_P x corners_Q) closed forms, about 0.1 to 1 microsecond per patch pair (more where non-parallel
// edges touch: about 1000 inner evaluations for such an edge pair).
#include <cstddef>

#include "core/types.h"
#include "patch/patch_set.h"

namespace radwalk {

// At most this many corners in a polygon given to the functions below (a quad clipped by a plane has 5).
inline constexpr int kMaxPolygonCorners = 8;

// The part of polygon p[0 .. count-1] on the closed front side of the plane (plane_point, unit plane_normal):
// Sutherland-Hodgman. Corners within `tolerance` of the plane count as on it (kept, not cut). Writes at most
// count + 1 corners to out (room for kMaxPolygonCorners) and returns their number (0 when nothing is in front:
// fewer than 3 corners, or every kept corner on the plane).
int clip_polygon_to_front(const Vec3* p, int count, const Vec3& plane_point, const Vec3& plane_normal,
                          double tolerance, Vec3* out);

// int_e int_f ln r ds dt (u_e . u_f) for the segments a0 -> a1 and b0 -> b1 (the edge-pair term of the contour
// integral above, without the 1 / 2 pi). 0 for a zero-length segment or perpendicular segments.
double edge_pair_log_integral(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1);

// The far-field rule for a pair of polygons (docs/theory/polygon_form_factor.md, "Far pairs"): with c the mean of
// a polygon's corners and R the largest distance of a corner from it, ratio = (|c_P - c_Q| - R_P - R_Q) / max(R_P,
// R_Q). For ratio >= kFarFieldRatio the point-to-point kernel cos_x cos_y / (pi r^2) is analytic in a Bernstein
// ellipse of parameter >= ratio in each quadrature variable, so an n-point Gauss-Legendre rule per variable errs by
// about ratio^(-2n) relative; points = the least n >= 2 with ratio^(-2n) <= 1e-14 (at most 8), 0 when the pair is
// not far (ratio below kFarFieldRatio, where the contour integral is used: its rounding there is below 1e-11
// relative).
inline constexpr double kFarFieldRatio = 32;
struct FarFieldRule {
  double ratio = 0;
  int points = 0;  // Gauss points per variable; 0: not far
};
FarFieldRule far_field_rule(const Vec3* p, int np, const Vec3* q, int nq);

// A_P F_PQ by the product Gauss rule of n points per variable on each polygon (a quadrilateral by its bilinear map,
// other polygons as fans of collapsed squares) of the kernel cos_x cos_y / (pi r^2), both cosines clamped at 0.
// Meant for far pairs (far_field_rule), where it is exact to about ratio^(-2n) and has no cancellation: every term
// is positive. n in [2, 8].
double far_field_exchange_area(const Vec3* p, int np, const Vec3& n_p, const Vec3* q, int nq, const Vec3& n_q,
                               int n);

// A_P F_PQ = A_Q F_QP (the exchange area) for planar polygons P (corners p[0 .. np-1], counter-clockwise about the
// unit normal n_p) and Q (q, nq, n_q) that see each other unoccluded; np, nq in [3, kMaxPolygonCorners - 1].
// Each is clipped to the front of the other's plane first (corners within 1e-12 of the polygons' size of a
// plane count as on it). Symmetric in exact arithmetic; swapping P and Q changes the result by rounding only.
double polygon_exchange_area(const Vec3* p, int np, const Vec3& n_p, const Vec3* q, int nq, const Vec3& n_q);

// The same for patches i and j of a PatchSet (its corners and normals), computed with the lower index as P, so
// patch_exchange_area(i, j) == patch_exchange_area(j, i) bit for bit. F_ij = result / A_i.
double patch_exchange_area(const PatchSet& patches, std::size_t i, std::size_t j);

// The clipped polygons of a pair: i's part in front of j's plane and j's part in front of i's (as above).
// Returns false when either is empty (F_ij = 0).
struct ClippedPair {
  Vec3 p[kMaxPolygonCorners], q[kMaxPolygonCorners];
  int np = 0, nq = 0;
};
bool clip_patch_pair(const PatchSet& patches, std::size_t i, std::size_t j, ClippedPair& out);

}  // namespace radwalk
