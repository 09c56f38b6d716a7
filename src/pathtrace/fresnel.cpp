#include "pathtrace/fresnel.h"

#include <algorithm>
#include <cmath>
#include <complex>

namespace radwalk {

double fresnel_dielectric(double cos_i, double eta) {
  cos_i = std::clamp(cos_i, -1.0, 1.0);
  // Light from the inside: swap the media.
  if (cos_i < 0) {
    eta = 1.0 / eta;
    cos_i = -cos_i;
  }
  // Snell's law; total internal reflection when sin_t >= 1.
  const double sin2_i = std::max(0.0, 1.0 - cos_i * cos_i);
  const double sin2_t = sin2_i / (eta * eta);
  if (sin2_t >= 1.0) return 1.0;
  const double cos_t = std::sqrt(1.0 - sin2_t);
  const double r_s = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const double r_p = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return 0.5 * (r_s * r_s + r_p * r_p);
}

double fresnel_conductor(double cos_i, double eta, double k) {
  using C = std::complex<double>;
  cos_i = std::clamp(cos_i, 0.0, 1.0);
  const C n(eta, k);
  const C n2 = n * n;
  const double sin2_i = 1.0 - cos_i * cos_i;
  const C s = std::sqrt(n2 - sin2_i);
  const C r_s = (cos_i - s) / (cos_i + s);
  const C r_p = (n2 * cos_i - s) / (n2 * cos_i + s);
  return 0.5 * (std::norm(r_s) + std::norm(r_p));
}

Rgb fresnel_conductor(double cos_i, const Rgb& eta, const Rgb& k) {
  return {fresnel_conductor(cos_i, eta[0], k[0]), fresnel_conductor(cos_i, eta[1], k[1]),
          fresnel_conductor(cos_i, eta[2], k[2])};
}

Rgb fresnel_schlick(double cos_i, const Rgb& F0) {
  const double m = 1.0 - std::clamp(std::abs(cos_i), 0.0, 1.0);
  return F0 + (1.0 - F0) * (m * m * m * m * m);
}

ConductorIor conductor_ior_from_f0(const Rgb& F0) {
  const Rgb r = F0.max(0.0).min(0.9999).sqrt();
  return {(1.0 + r) / (1.0 - r), Rgb::Zero()};
}

}  // namespace radwalk
