#pragma once
// The exact unoccluded form factor from a point to a planar convex polygon (Lambert's formula; derivation and
// sources in docs/theory/point_polygon_form_factor.md):
//   F(x -> P) = int_P cos(t_x) cos(t_y) / (pi |y - x|^2) dA_y
//             = (1 / 2 pi) | sum_k gamma_k n . (R_k x R_{k+1}) / |R_k x R_{k+1}| |,
// R_k = p_k - x the corners of P seen from x, gamma_k = angle(R_k, R_{k+1}) in [0, pi], n the unit normal at x.
// This holds for a polygon entirely on the front side of x's plane (n . (y - x) >= 0 on P); P is first clipped to
// that half space (Sutherland-Hodgman against the plane through x with normal n), which is the cos(t_x) > 0
// factor of the integrand. The emitting side: only the front of P (its normal n_P, corners counter-clockwise
// about it) radiates, so the result is 0 when x is not strictly in front of P's plane: n_P . (x - p_0) <=
// kPlaneTolerance max_k |p_k - x| (a point in P's plane, up to rounding, sees P edge-on).
// Absolute value: the signed sum is +- the projected solid angle according to the corners' order seen from x.
#include <cstddef>

#include "core/types.h"
#include "patch/patch_set.h"

namespace radwalk {

inline constexpr double kPlaneTolerance = 1e-9;  // relative: a point this close to P's plane lies in it

// F(x -> P) for the convex polygon corners[0 .. count-1] (count 3 or 4, counter-clockwise about normal_P) from
// the point x with unit normal n (the cos(t_x) > 0 side). 0 when P is behind x's plane or x behind P's.
double point_polygon_form_factor(const Vec3& x, const Vec3& n, const Vec3* corners, int count, const Vec3& normal_P);

// The same for patch e of a PatchSet.
double point_patch_form_factor(const Vec3& x, const Vec3& n, const PatchSet& patches, std::size_t e);

// False when F(x -> e) = 0 for every point x of patch i: no corner of i strictly in front of e's plane, or no
// corner of e strictly in front of i's plane (both are linear conditions, so the corners decide). True otherwise.
bool patch_may_see(const PatchSet& patches, std::size_t i, std::size_t e);

}  // namespace radwalk
