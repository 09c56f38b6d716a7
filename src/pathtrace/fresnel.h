#pragma once
// Fresnel reflectance of a smooth interface for unpolarised light (dimensionless, in [0, 1]).
//
// Dielectric: eta = eta_t / eta_i is the relative index of the side opposite the normal over the normal's side;
// cos_i = dot(w, n) is signed: cos_i < 0 means the light arrives from the inside, and eta is inverted.
//   F = (r_s^2 + r_p^2) / 2, r_s = (cos_i - eta cos_t) / (cos_i + eta cos_t), r_p = (eta cos_i - cos_t) /
//   (eta cos_i + cos_t), with Snell's law sin_t = sin_i / eta; F = 1 under total internal reflection.
// Conductor: complex index eta + i k, cos_i >= 0:
//   F = (|r_s|^2 + |r_p|^2) / 2, r_s = (cos_i - s) / (cos_i + s), r_p = (n^2 cos_i - s) / (n^2 cos_i + s),
//   s = sqrt(n^2 - sin_i^2), n = eta + i k (complex arithmetic). With k = 0 and eta > 1 it equals the dielectric.
// MTL has no conductor index: radwalk takes Ks as the normal-incidence reflectance F0 and uses the real index
// with that F0, eta = (1 + sqrt(F0)) / (1 - sqrt(F0)), k = 0 (conductor_ior_from_f0). The curve then rises from
// F0 at normal incidence to 1 at grazing incidence, like a metal without the slight dip before grazing.
#include "core/types.h"

namespace radwalk {

double fresnel_dielectric(double cos_i, double eta);

double fresnel_conductor(double cos_i, double eta, double k);
Rgb fresnel_conductor(double cos_i, const Rgb& eta, const Rgb& k);

// Schlick's approximation F0 + (1 - F0) (1 - cos_i)^5 (for comparison; the BSDFs use the exact forms).
Rgb fresnel_schlick(double cos_i, const Rgb& F0);

struct ConductorIor {
  Rgb eta;
  Rgb k;
};
// Real index with normal-incidence reflectance F0 per channel (F0 clamped to [0, 0.9999]); k = 0.
ConductorIor conductor_ior_from_f0(const Rgb& F0);

}  // namespace radwalk
