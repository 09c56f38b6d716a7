#pragma once
// The isotropic GGX (Trowbridge-Reitz) microfacet distribution with roughness alpha, in the local frame (+z is
// the macro-surface normal), and Smith's masking-shadowing (Heitz 2014, "Understanding the masking-shadowing
// function"; Walter et al. 2007).
//   D(wm)      = 1 / (pi alpha^2 cos^4(theta_m) (1 + tan^2(theta_m) / alpha^2)^2)     (1/sr; int D cos = 1)
//   Lambda(w)  = (sqrt(1 + alpha^2 tan^2(theta)) - 1) / 2
//   G1(w)      = 1 / (1 + Lambda(w))
//   G(wo, wi)  = 1 / (1 + Lambda(wo) + Lambda(wi))             (height-correlated masking-shadowing)
//   D_wo(wm)   = G1(wo) max(0, wo.wm) D(wm) / cos(wo)          (distribution of visible normals, 1/sr)
// Sampling triplet for visible normals (Heitz 2018, "Sampling the GGX distribution of visible normals"):
// sample_visible_normal, visible_normal_pdf (= D_wo); no closed-form inverse is provided.
#include "core/types.h"

namespace radwalk {

class Ggx {
 public:
  explicit Ggx(double alpha) : alpha_(alpha) {}
  double alpha() const { return alpha_; }
  double D(const Vec3& wm) const;
  double lambda(const Vec3& w) const;
  double G1(const Vec3& w) const { return 1.0 / (1.0 + lambda(w)); }
  double G(const Vec3& wo, const Vec3& wi) const { return 1.0 / (1.0 + lambda(wo) + lambda(wi)); }
  // wo.z() > 0; u in [0, 1)^2. Returns a unit micro-normal with wm.z() >= 0 and wo.wm >= 0.
  Vec3 sample_visible_normal(const Vec3& wo, double u1, double u2) const;
  double visible_normal_pdf(const Vec3& wo, const Vec3& wm) const;

 private:
  double alpha_;
};

}  // namespace radwalk
