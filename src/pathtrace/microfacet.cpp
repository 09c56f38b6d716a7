#include "pathtrace/microfacet.h"

#include <cmath>

#include "pathtrace/fresnel.h"

namespace radwalk {

Rgb MicrofacetConductor::fresnel(double cos_h) const { return fresnel_conductor(cos_h, eta_, k_); }

Rgb MicrofacetConductor::f(const Vec3& wo, const Vec3& wi) const {
  if (wo.z() <= 0 || wi.z() <= 0) return Rgb::Zero();
  Vec3 wm = wo + wi;
  if (wm.squaredNorm() == 0) return Rgb::Zero();
  wm.normalize();
  const double c = wo.dot(wm);
  return fresnel(c) * (ggx_.D(wm) * ggx_.G(wo, wi) / (4.0 * wo.z() * wi.z()));
}

double MicrofacetConductor::pdf(const Vec3& wo, const Vec3& wi) const {
  if (wo.z() <= 0 || wi.z() <= 0) return 0.0;
  Vec3 wm = wo + wi;
  if (wm.squaredNorm() == 0) return 0.0;
  wm.normalize();
  const double c = wo.dot(wm);
  if (c <= 0) return 0.0;
  return ggx_.visible_normal_pdf(wo, wm) / (4.0 * c);
}

std::optional<BsdfSample> MicrofacetConductor::sample(const Vec3& wo, double u1, double u2, double) const {
  if (wo.z() <= 0) return std::nullopt;
  // Visible normal, then mirror reflection about it.
  const Vec3 wm = ggx_.sample_visible_normal(wo, u1, u2);
  const double c = wo.dot(wm);
  if (c <= 0) return std::nullopt;
  const Vec3 wi = (2.0 * c * wm - wo).normalized();
  if (wi.z() <= 0) return std::nullopt;  // reflected below the surface: the sample carries no energy
  const double pdf = ggx_.visible_normal_pdf(wo, wm) / (4.0 * c);
  if (!(pdf > 0)) return std::nullopt;
  const Rgb weight = fresnel(c) * (ggx_.G(wo, wi) / ggx_.G1(wo));
  return BsdfSample{wi, weight, pdf, false};
}

}  // namespace radwalk
