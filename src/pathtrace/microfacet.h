#pragma once
// Rough conductor: the Torrance-Sparrow BRDF with the GGX distribution and height-correlated Smith
// masking-shadowing (ggx.h) and the conductor Fresnel term (fresnel.h):
//   f(wo, wi) = D(wm) G(wo, wi) F(wo.wm) / (4 cos(wo) cos(wi)),   wm = normalize(wo + wi),   wo, wi above.
// Sampling: a visible normal wm ~ D_wo, then wi = reflect(wo, wm); pdf(wi) = D_wo(wm) / (4 wo.wm), and the
// weight f cos(wi) / pdf = F(wo.wm) G(wo, wi) / G1(wo) <= F. Energy is lost to single scattering only (no
// multiple-scattering compensation): albedo < 1 even with F = 1, approaching 1 as alpha -> 0.
#include <optional>

#include "pathtrace/bsdf_sample.h"
#include "pathtrace/ggx.h"

namespace radwalk {

class MicrofacetConductor {
 public:
  MicrofacetConductor(double alpha, const Rgb& eta, const Rgb& k) : ggx_(alpha), eta_(eta), k_(k) {}
  Rgb f(const Vec3& wo, const Vec3& wi) const;
  double pdf(const Vec3& wo, const Vec3& wi) const;
  std::optional<BsdfSample> sample(const Vec3& wo, double u1, double u2, double uc) const;
  const Ggx& distribution() const { return ggx_; }

 private:
  Rgb fresnel(double cos_h) const;
  Ggx ggx_;
  Rgb eta_, k_;
};

}  // namespace radwalk
