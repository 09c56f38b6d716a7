#pragma once
// EmbreeVisibility: the Visibility interface over one Embree 3 device and scene built from a PatchSet.
//
// Contract
// - Geometry: every patch becomes one Embree primitive (triangles in a triangle geometry, quads in a quad
//   geometry); a hit is mapped back to its patch index. A quad (p0, p1, p2, p3) is handed to Embree as
//   (p1, p2, p3, p0) so that Embree's split diagonal is p0-p2, the same split as sample_patch_point and
//   BruteForceVisibility use (this matters only for non-planar quads).
// - Hit::front = dot(ray direction, patch normal) < 0, with the PatchSet's normal (not Embree's Ng).
// - Two-sided faces (PatchSet::two_sided): their patches go into geometries of their own (triangles, quads) with an
//   intersection filter that rejects a hit arriving at a patch's back (the same float test as Hit::front), so the
//   ray goes on to the coincident patch of the other side, which it reaches from its front. A one-sided scene
//   without contact pairs builds exactly the geometries it built before (no filter, the same hits).
// - Contact pairs (patch/contact_pairs.h: two front patches on the same corners back to back, e.g. a floor piece
//   cut along a box's footprint and the box's bottom on it): their patches go into the filtered geometries too,
//   whose filter rejects a hit arriving at a pair patch's front. Such a front can only be reached through its
//   partner, which lies on the same points facing the other way, at the same t up to float rounding; without the
//   filter either could be hit. With it the ray stops at the partner's back, the member on the ray's side: a ray
//   from inside the box towards its bottom hits the bottom (a back hit), never the floor piece under it, and a
//   ray from below the floor hits the floor piece's back. Both are absorbing backs, so no figure changes; the
//   choice is only made deterministic. A patch that is both (a two-sided face's front in a pair) rejects both
//   sides: its own back patch and its partner take the hits.
// - Hit::t is the ray parameter in the mesh's length unit (directions are unit length); rays are traced in
//   single precision, so t and the hit patch near a shared edge agree with exact arithmetic only up to float
//   rounding. Origins should come from spawn_ray (ray_offset.h), which keeps them off their own patch.
// - The scene is built with RTC_SCENE_FLAG_ROBUST (watertight: a closed mesh with shared edges leaks no ray).
// - Embree errors reported through the device error callback become std::runtime_error ("embree: ...") from the
//   constructor; a PatchSet with corner indices out of range or non-finite points is an InputError.
// - Thread-safe: all query methods are const and may be called concurrently. Non-copyable, non-movable (RAII
//   owner of the device and the scene).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "patch/patch_set.h"
#include "visibility/visibility.h"

namespace radwalk {

struct EmbreeOptions {
  // Passed to rtcNewDevice. "isa=avx2" measured a few percent faster than the AVX-512 default on this
  // machine (docs/dependencies.md, "Embree"); Embree falls back to a lower ISA when the CPU lacks AVX2.
  std::string device_config = "isa=avx2";
  bool robust = true;  // RTC_SCENE_FLAG_ROBUST
};

class EmbreeVisibility final : public Visibility {
 public:
  explicit EmbreeVisibility(const PatchSet& patches, const EmbreeOptions& options = {});
  ~EmbreeVisibility() override;
  EmbreeVisibility(const EmbreeVisibility&) = delete;
  EmbreeVisibility& operator=(const EmbreeVisibility&) = delete;

  Hit intersect(const Ray& ray) const override;
  bool occluded(const Ray& ray) const override;
  // Batches: packets of 16 (rtcIntersect16) for intersect, streams (rtcOccluded1M) for occluded: both measured
  // faster than single rays on incoherent rays (bench/bench_formfactors.cpp). A Ray batch is rounded to
  // RayPackets of 16 and traced as such; a RayPacket goes to rtcIntersect16 as it is.
  void intersect(const Ray* rays, Hit* hits, std::size_t n) const override;
  void occluded(const Ray* rays, bool* out, std::size_t n) const override;
  void intersect(const RayPacket& rays, Hit* hits) const override;

  std::size_t patch_count() const { return normal_.size(); }

  struct Device;  // opaque: Embree handles and the error record (keeps <embree3/rtcore.h> out of this header)

 private:
  Hit make_hit(unsigned geom_id, unsigned prim_id, float t, const float dir[3]) const;

 public:
  // What the filter rejects of a patch: hits arriving at its back (two-sided faces), at its front (contact pairs).
  static constexpr std::uint8_t kRejectBack = 1, kRejectFront = 2;
  // The patches of one Embree geometry (primID -> patch), the normals and the rejected sides, for the filter.
  struct Primitives {
    std::vector<PatchIndex> patch;
    const std::vector<Eigen::Vector3f>* normal = nullptr;
    const std::vector<std::uint8_t>* reject = nullptr;
  };

 private:
  std::unique_ptr<Device> device_;
  // Geometries in the order triangles, quads, filtered triangles, filtered quads (the patches that reject a side);
  // empty ones are not attached.
  std::vector<Primitives> primitives_ = std::vector<Primitives>(4);
  std::vector<unsigned> geometry_kind_;   // Embree geomID -> index into primitives_
  std::vector<Eigen::Vector3f> normal_;   // patch normals, for Hit::front
  std::vector<std::uint8_t> reject_;      // per patch: kRejectBack | kRejectFront, 0 for none
};

}  // namespace radwalk
