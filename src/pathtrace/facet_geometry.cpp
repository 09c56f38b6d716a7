#include "pathtrace/facet_geometry.h"

#include "patch/patch_set.h"

namespace radwalk {

FacetGeometry::FacetGeometry(const PatchSet& patches) : patches_(patches), eps_(ray_epsilon(patches)) {
  offsets_.reserve(patches.size());
  points_.reserve(patches.size());
  for (std::size_t i = 0; i < patches.size(); ++i) {
    offsets_.push_back(patch_ray_offset(patches, i, eps_));
    points_.emplace_back(patches, i);
  }
}

Vec3 FacetGeometry::normal(PatchIndex i, const Vec3&) const { return patches_.normal[static_cast<std::size_t>(i)]; }

Vec3 FacetGeometry::sample_point(PatchIndex i, double u1, double u2) const {
  return points_[static_cast<std::size_t>(i)].point(u1, u2);
}

Ray FacetGeometry::spawn_ray(PatchIndex i, const Vec3& x, const Vec3& d) const {
  return radwalk::spawn_ray(offsets_[static_cast<std::size_t>(i)], x, d);
}

Ray FacetGeometry::spawn_shadow_ray(PatchIndex i, const Vec3& x, const Vec3& w, double r, const Vec3& y,
                                    const Vec3& n_y) const {
  return stop_before_plane(spawn_ray(i, x, w), r, y, n_y, 4 * eps_);
}

void FacetGeometry::prefetch(PatchIndex i) const {
  const auto k = static_cast<std::size_t>(i);
  __builtin_prefetch(&patches_.normal[k]);
  __builtin_prefetch(&offsets_[k]);
  __builtin_prefetch(reinterpret_cast<const char*>(&offsets_[k]) + sizeof(PatchRayOffset) - 1);
}

}  // namespace radwalk
