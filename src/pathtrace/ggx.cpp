#include "pathtrace/ggx.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace radwalk {

double Ggx::D(const Vec3& wm) const {
  const double cos2 = wm.z() * wm.z();
  if (wm.z() <= 0) return 0.0;
  const double a2 = alpha_ * alpha_;
  // Equivalent form: a2 / (pi ((a2 - 1) cos^2 + 1)^2), stable at tan -> infinity.
  const double d = (a2 - 1.0) * cos2 + 1.0;
  return a2 / (kPi * d * d);
}

double Ggx::lambda(const Vec3& w) const {
  const double cos2 = w.z() * w.z();
  if (cos2 <= 0) return std::numeric_limits<double>::infinity();
  const double tan2 = std::max(0.0, 1.0 - cos2) / cos2;
  return 0.5 * (std::sqrt(1.0 + alpha_ * alpha_ * tan2) - 1.0);
}

Vec3 Ggx::sample_visible_normal(const Vec3& wo, double u1, double u2) const {
  // Stretch the view direction to the configuration where alpha = 1 (a hemisphere of normals).
  const Vec3 vh = Vec3(alpha_ * wo.x(), alpha_ * wo.y(), wo.z()).normalized();
  // Orthonormal basis around vh.
  const double len2 = vh.x() * vh.x() + vh.y() * vh.y();
  const Vec3 t1 = len2 > 0 ? Vec3(-vh.y(), vh.x(), 0) / std::sqrt(len2) : Vec3(1, 0, 0);
  const Vec3 t2 = vh.cross(t1);
  // Uniform point on the disk, warped onto the projected visible half of the hemisphere.
  const double r = std::sqrt(u1);
  const double phi = 2.0 * kPi * u2;
  const double p1 = r * std::cos(phi);
  double p2 = r * std::sin(phi);
  const double s = 0.5 * (1.0 + vh.z());
  p2 = (1.0 - s) * std::sqrt(std::max(0.0, 1.0 - p1 * p1)) + s * p2;
  // Lift to the hemisphere and unstretch.
  const Vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
  return Vec3(alpha_ * nh.x(), alpha_ * nh.y(), std::max(1e-12, nh.z())).normalized();
}

double Ggx::visible_normal_pdf(const Vec3& wo, const Vec3& wm) const {
  if (wo.z() <= 0) return 0.0;
  const double c = wo.dot(wm);
  if (c <= 0) return 0.0;
  return G1(wo) * c * D(wm) / wo.z();
}

}  // namespace radwalk
