#pragma once
// Visibility: "which patch does this ray hit first?" as an interface, so algorithms can run on Embree or on an
// analytic stand-in in tests.
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
  bool front = false;     // true when the ray arrives against the patch normal (dot(direction, normal) < 0)
  bool missed() const { return patch < 0; }
};

class Visibility {
 public:
  virtual ~Visibility() = default;
  // First patch hit along the ray within (0, tmax].
  virtual Hit intersect(const Ray& ray) const = 0;
  // True when anything is hit within (0, tmax).
  virtual bool occluded(const Ray& ray) const = 0;
};

}  // namespace radwalk
