#pragma once
// Lambertian reflection: f(wo, wi) = R / pi (1/sr) for wo, wi both above the surface (z > 0), else 0.
// Sampling is cosine-weighted: pdf(wi) = cos(wi) / pi, so the sample weight f cos / pdf = R.
// Albedo (directional-hemispherical reflectance) = R for every wo.
#include <optional>

#include "core/sampling.h"
#include "pathtrace/bsdf_sample.h"

namespace radwalk {

class Lambertian {
 public:
  explicit Lambertian(const Rgb& R) : R_(R) {}
  Rgb f(const Vec3& wo, const Vec3& wi) const {
    return (wo.z() > 0 && wi.z() > 0) ? Rgb(R_ * kInvPi) : Rgb::Zero();
  }
  double pdf(const Vec3& wo, const Vec3& wi) const { return wo.z() > 0 ? cosine_hemisphere_pdf(wi) : 0.0; }
  std::optional<BsdfSample> sample(const Vec3& wo, double u1, double u2, double /*uc*/) const {
    if (wo.z() <= 0) return std::nullopt;
    const Vec3 wi = sample_cosine_hemisphere(u1, u2);
    if (wi.z() <= 0) return std::nullopt;
    return BsdfSample{wi, R_, cosine_hemisphere_pdf(wi), false};
  }
  const Rgb& R() const { return R_; }

 private:
  Rgb R_;
};

}  // namespace radwalk
