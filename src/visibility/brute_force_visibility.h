#pragma once
// BruteForceVisibility: the Visibility interface by testing every patch, in double precision. O(N) per ray; an
// analytic stand-in for EmbreeVisibility in tests.
//
// A triangle is hit when the ray meets it at t in (0, tmax] with barycentric coordinates in [0, 1] (edges
// included, so shared edges never leak); a quad (p0, p1, p2, p3) is the two triangles (p0, p1, p2), (p0, p2, p3)
// (the split sample_patch_point and EmbreeVisibility use). The nearest hit wins; among equal t, the lower patch
// index. Hit::front = dot(direction, normal) < 0. A patch of a two-sided face (PatchSet::two_sided) is skipped by
// a ray arriving at its back, and a patch of a contact pair (patch/contact_pairs.h) by a ray arriving at its front,
// as in EmbreeVisibility. Keeps a reference to the PatchSet: it must outlive this object.
#include <cstdint>
#include <optional>
#include <vector>

#include "patch/patch_set.h"
#include "visibility/visibility.h"

namespace radwalk {

// The ray parameter t in (0, tmax] where `ray` meets patch i, if it does (double precision, edges included).
std::optional<double> intersect_patch(const PatchSet& patches, std::size_t i, const Ray& ray);

class BruteForceVisibility final : public Visibility {
 public:
  explicit BruteForceVisibility(const PatchSet& patches);
  using Visibility::intersect;
  using Visibility::occluded;
  Hit intersect(const Ray& ray) const override;
  bool occluded(const Ray& ray) const override;

 private:
  const PatchSet& patches_;
  std::vector<std::int32_t> pair_;  // contact_pair_ids(patches_)
};

}  // namespace radwalk
