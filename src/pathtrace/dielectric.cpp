#include "pathtrace/dielectric.h"

#include <cmath>

#include "pathtrace/fresnel.h"

namespace radwalk {

std::optional<Vec3> refract_local(const Vec3& wo, double eta_rel) {
  // Work with the normal on wo's side, then t = -wo / eta + (cos_o / eta - cos_t) n.
  const double sign = wo.z() >= 0 ? 1.0 : -1.0;
  const double cos_o = std::abs(wo.z());
  const double sin2_t = std::max(0.0, 1.0 - cos_o * cos_o) / (eta_rel * eta_rel);
  if (sin2_t >= 1.0) return std::nullopt;
  const double cos_t = std::sqrt(1.0 - sin2_t);
  Vec3 t = -wo / eta_rel;
  t.z() += sign * (cos_o / eta_rel - cos_t);
  return t.normalized();
}

std::optional<BsdfSample> Dielectric::sample(const Vec3& wo, double, double, double uc) const {
  const double F = fresnel_dielectric(wo.z(), eta_);
  // Reflection lobe.
  if (uc < F) return BsdfSample{reflect_local(wo), Rgb::Ones(), F, true};
  // Refraction lobe: into the inside when wo is outside, and back out otherwise.
  const double eta_rel = wo.z() > 0 ? eta_ : 1.0 / eta_;
  const auto wt = refract_local(wo, eta_rel);
  if (!wt) return BsdfSample{reflect_local(wo), Rgb::Ones(), 1.0, true};
  return BsdfSample{*wt, Rgb::Ones(), 1.0 - F, true};
}

}  // namespace radwalk
