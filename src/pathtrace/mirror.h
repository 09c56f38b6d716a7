#pragma once
// Perfect mirror: f(wo, wi) = R delta(wi - reflect(wo)) / |cos(wi)|; sampling returns the mirror direction with
// weight R (delta lobe, probability 1). Albedo = R for every wo above the surface.
#include <optional>

#include "pathtrace/bsdf_sample.h"

namespace radwalk {

class Mirror {
 public:
  explicit Mirror(const Rgb& R) : R_(R) {}
  Rgb f(const Vec3&, const Vec3&) const { return Rgb::Zero(); }
  double pdf(const Vec3&, const Vec3&) const { return 0.0; }
  std::optional<BsdfSample> sample(const Vec3& wo, double, double, double) const {
    if (wo.z() <= 0) return std::nullopt;
    return BsdfSample{reflect_local(wo), R_, 1.0, true};
  }

 private:
  Rgb R_;
};

}  // namespace radwalk
