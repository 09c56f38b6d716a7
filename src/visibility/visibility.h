#pragma once
// Visibility: "which patch does this ray hit first?" as an interface, so algorithms can run on Embree or on an
// analytic stand-in in tests.
#include <cstddef>
#include <cstdint>
#include <limits>

#include "core/types.h"

namespace radwalk {

struct Ray {
  Vec3 origin;
  Vec3 direction;  // unit length
  double tmax = std::numeric_limits<double>::infinity();
};

struct Hit {
  PatchIndex patch = -1;  // -1: the ray left the scene
  double t = std::numeric_limits<double>::infinity();
  // True when the ray arrives against the patch normal (dot(direction, normal) < 0). False is a back hit on a
  // one-sided face; a ray reaching a two-sided face hits the patch of the side it arrives on, always front
  // (patch/patch_set.h, "Sides").
  bool front = false;
  bool missed() const { return patch < 0; }
};

struct RayPacket;  // ray_packet.h

class Visibility {
 public:
  virtual ~Visibility() = default;
  // First patch hit along the ray within (0, tmax].
  virtual Hit intersect(const Ray& ray) const = 0;
  // True when anything is hit within (0, tmax).
  virtual bool occluded(const Ray& ray) const = 0;

  // Batches: hits[k] = intersect(rays[k]) and out[k] = occluded(rays[k]) for k < n. Implementations override
  // these where packets or streams are faster (EmbreeVisibility); the results equal the single-ray calls.
  virtual void intersect(const Ray* rays, Hit* hits, std::size_t n) const {
    for (std::size_t k = 0; k < n; ++k) hits[k] = intersect(rays[k]);
  }
  virtual void occluded(const Ray* rays, bool* out, std::size_t n) const {
    for (std::size_t k = 0; k < n; ++k) out[k] = occluded(rays[k]);
  }
  // A packet in single precision: hits[k] = intersect(rays.ray(k)) for k < rays.count (ray_packet.h).
  virtual void intersect(const RayPacket& rays, Hit* hits) const;
};

}  // namespace radwalk
