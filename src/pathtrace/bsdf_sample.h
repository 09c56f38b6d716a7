#pragma once
// The result of sampling a BSDF lobe, in the local shading frame (normal = +z; directions point away from the
// surface; wo is where the light goes, wi where it comes from).
#include "core/types.h"

namespace radwalk {

struct BsdfSample {
  Vec3 wi;         // sampled direction, unit length
  Rgb weight;      // f(wo, wi) |cos(wi)| / pdf: the factor the path throughput is multiplied by
  double pdf = 0;  // solid-angle density of wi; for a delta lobe the discrete probability of the chosen lobe
  bool delta = false;  // a Dirac lobe (mirror, refraction): f and pdf cannot be evaluated, only sampled
};

// Mirror direction of w about +z.
inline Vec3 reflect_local(const Vec3& w) { return {-w.x(), -w.y(), w.z()}; }

}  // namespace radwalk
