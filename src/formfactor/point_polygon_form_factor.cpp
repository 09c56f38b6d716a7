#include "formfactor/point_polygon_form_factor.h"

#include <algorithm>
#include <cmath>

namespace radwalk {

double point_polygon_form_factor(const Vec3& x, const Vec3& n, const Vec3* corners, int count,
                                 const Vec3& normal_P) {
  // The emitting side: x strictly in front of P's plane, by more than rounding (kPlaneTolerance of x's distance to
  // P's corners). A point in P's plane (a point of P itself, or of a coplanar neighbour) sees P edge-on: 0, where
  // the sum below, whose terms are then all +-gamma_k, would give 1 inside P's outline.
  double reach = 0;
  for (int k = 0; k < count; ++k) reach = std::max(reach, (corners[k] - x).norm());
  if (!(normal_P.dot(x - corners[0]) > kPlaneTolerance * reach)) return 0.0;
  // Clip P to the half space n . (y - x) >= 0 (a convex polygon stays convex; at most count + 1 corners).
  Vec3 R[8];
  int m = 0;
  for (int k = 0; k < count; ++k) {
    const Vec3 a = corners[k] - x, b = corners[(k + 1) % count] - x;
    const double da = n.dot(a), db = n.dot(b);
    if (da >= 0) R[m++] = a;
    if ((da >= 0) != (db >= 0)) {
      const double t = da / (da - db);  // the crossing of the plane on edge a -> b
      R[m++] = a + t * (b - a);
    }
  }
  if (m < 3) return 0.0;
  // Lambert: (1 / 2 pi) sum_k gamma_k n . unit(R_k x R_{k+1}).
  double sum = 0;
  for (int k = 0; k < m; ++k) {
    const Vec3& a = R[k];
    const Vec3& b = R[(k + 1) % m];
    const Vec3 c = a.cross(b);
    const double cn = c.norm();
    if (!(cn > 0)) continue;  // a degenerate edge (two corners on one line through x) adds nothing
    const double gamma = std::atan2(cn, a.dot(b));
    sum += gamma * n.dot(c) / cn;
  }
  return std::abs(sum) / (2 * kPi);
}

double point_patch_form_factor(const Vec3& x, const Vec3& n, const PatchSet& patches, std::size_t e) {
  const int count = patches.corner_count(e);
  Vec3 c[4];
  for (int k = 0; k < count; ++k) c[k] = patches.corner(e, k);
  return point_polygon_form_factor(x, n, c, count, patches.normal[e]);
}

namespace {
// True when some corner of patch a lies strictly in front of the plane of patch b.
bool in_front(const PatchSet& patches, std::size_t a, std::size_t b) {
  const Vec3& n = patches.normal[b];
  const Vec3& p = patches.corner(b, 0);
  for (int c = 0; c < patches.corner_count(a); ++c)
    if (n.dot(patches.corner(a, c) - p) > 0) return true;
  return false;
}
}  // namespace

bool patch_may_see(const PatchSet& patches, std::size_t i, std::size_t e) {
  return in_front(patches, i, e) && in_front(patches, e, i);
}

}  // namespace radwalk
