#pragma once
// FacetGeometry: the patches of a PatchSet as the planar triangles and quads they are (SurfaceGeometry).
//   normal(i, x)          = PatchSet::normal[i], constant over the patch;
//   sample_point(i, u)    = sample_patch_point's point (pdf 1 / A_i) from each patch's PatchPointSampler;
//   spawn_ray(i, x, d)    = visibility/ray_offset.h's scale-aware offset with the scene's ray epsilon;
// The per-patch parts of both are precomputed (160 bytes per patch).
//   spawn_shadow_ray      = spawn_ray's ray, short of the light point's plane by 4 eps more than the base's margin
//                           (the offset moves the origin by up to about eps towards that plane);
//   sees_itself(i)        = false (a plane does not see itself);
//   prefetch(i)           asks for patch i's normal and ray offset.
// Keeps a reference to the patches (they must outlive it).
#include <vector>

#include "patch/patch_point_sampler.h"
#include "pathtrace/surface_geometry.h"
#include "visibility/ray_offset.h"

namespace radwalk {

class FacetGeometry final : public SurfaceGeometry {
 public:
  explicit FacetGeometry(const PatchSet& patches);
  Vec3 normal(PatchIndex i, const Vec3& x) const override;
  Vec3 sample_point(PatchIndex i, double u1, double u2) const override;
  Ray spawn_ray(PatchIndex i, const Vec3& x, const Vec3& d) const override;
  Ray spawn_shadow_ray(PatchIndex i, const Vec3& x, const Vec3& w, double r, const Vec3& y,
                       const Vec3& n_y) const override;
  bool sees_itself(PatchIndex) const override { return false; }
  void prefetch(PatchIndex i) const override;

 private:
  const PatchSet& patches_;
  double eps_ = 0;                          // ray_epsilon(patches)
  std::vector<PatchRayOffset> offsets_;     // patch_ray_offset of every patch, with eps = ray_epsilon(patches)
  std::vector<PatchPointSampler> points_;  // PatchPointSampler of every patch
};

}  // namespace radwalk
