#pragma once
// Smooth conductor: a mirror whose reflectance is the conductor Fresnel term F(cos(wo); eta, k) per channel
// (fresnel.h). Sampling returns the mirror direction with weight F (delta lobe). Albedo = F(cos(wo)); with
// k -> infinity F -> 1 (a perfect mirror).
#include <optional>

#include "pathtrace/bsdf_sample.h"
#include "pathtrace/fresnel.h"

namespace radwalk {

class Conductor {
 public:
  Conductor(const Rgb& eta, const Rgb& k) : eta_(eta), k_(k) {}
  Rgb f(const Vec3&, const Vec3&) const { return Rgb::Zero(); }
  double pdf(const Vec3&, const Vec3&) const { return 0.0; }
  std::optional<BsdfSample> sample(const Vec3& wo, double, double, double) const {
    if (wo.z() <= 0) return std::nullopt;
    return BsdfSample{reflect_local(wo), fresnel_conductor(wo.z(), eta_, k_), 1.0, true};
  }

 private:
  Rgb eta_, k_;
};

}  // namespace radwalk
