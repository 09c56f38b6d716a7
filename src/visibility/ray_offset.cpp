#include "visibility/ray_offset.h"

#include <cfloat>
#include <cmath>
#include <limits>

namespace radwalk {

double ray_epsilon(const PatchSet& patches) {
  double max_abs = 0;
  for (const auto& p : patches.points) max_abs = std::max(max_abs, p.cwiseAbs().maxCoeff());
  const double eps = std::max(1e-6 * patches.scene_extent(), 8.0 * FLT_EPSILON * max_abs);
  return eps > 0 ? eps : FLT_MIN;  // a degenerate scene (one point) still gets a positive offset
}

PatchRayOffset patch_ray_offset(const PatchSet& patches, std::size_t patch, double eps) {
  PatchRayOffset o;
  o.normal_eps = eps * patches.normal[patch];
  o.centroid = patches.centroid[patch];
  // d_i: smallest distance from the centroid to an edge line.
  double d = std::numeric_limits<double>::infinity();
  const int m = patches.corner_count(patch);
  for (int k = 0; k < m; ++k) {
    const Vec3 a = patches.corner(patch, k), e = patches.corner(patch, (k + 1) % m) - a;
    const double len = e.norm();
    if (len > 0) d = std::min(d, e.cross(o.centroid - a).norm() / len);
  }
  o.pull = d > eps ? eps / d : 1.0;
  return o;
}

}  // namespace radwalk
