#pragma once
// Smooth dielectric interface with relative index eta = n_inside / n_outside (outside = the normal's side).
// Reflection with probability F = fresnel_dielectric(cos(wo), eta), refraction (Snell) with probability 1 - F;
// total internal reflection when Snell has no solution (F = 1). Both lobes are deltas and, chosen in proportion
// to their energy, have sample weight 1, so R + T = 1 exactly.
// Radiance scaling across the interface (eta^2) is not applied: it cancels on every path that leaves the
// medium it entered, which holds when camera and emitters are outside every dielectric.
#include <optional>

#include "pathtrace/bsdf_sample.h"

namespace radwalk {

class Dielectric {
 public:
  explicit Dielectric(double eta) : eta_(eta) {}
  Rgb f(const Vec3&, const Vec3&) const { return Rgb::Zero(); }
  double pdf(const Vec3&, const Vec3&) const { return 0.0; }
  // wo may lie on either side (wo.z < 0: inside); uc chooses the lobe.
  std::optional<BsdfSample> sample(const Vec3& wo, double u1, double u2, double uc) const;
  double eta() const { return eta_; }

 private:
  double eta_;
};

// Refracted direction of wo through the plane z = 0 with relative index eta_rel = n_t / n_i (the side wo is
// on has n_i); nullopt under total internal reflection.
std::optional<Vec3> refract_local(const Vec3& wo, double eta_rel);

}  // namespace radwalk
