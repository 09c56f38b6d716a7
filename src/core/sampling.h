#pragma once
// Sampling triplets (docs/ARCHITECTURE.md, convention 4): sample, pdf and inverse for the warps radwalk uses.
// u = (u1, u2) are uniform numbers in [0, 1)^2.
#include <cmath>

#include "core/types.h"

namespace radwalk {

// Cosine-weighted direction on the hemisphere about +z (Malley's method: uniform disk, then project up).
// pdf(w) = cos(theta) / pi per steradian.
inline Vec3 sample_cosine_hemisphere(double u1, double u2) {
  const double r = std::sqrt(u1);
  const double phi = 2.0 * kPi * u2;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - u1))};
}
inline double cosine_hemisphere_pdf(const Vec3& w) { return w.z() > 0 ? w.z() * kInvPi : 0.0; }
// Inverse of sample_cosine_hemisphere: the (u1, u2) that maps to w (w.z() > 0, |w| = 1).
inline Eigen::Vector2d invert_cosine_hemisphere(const Vec3& w) {
  double phi = std::atan2(w.y(), w.x());
  if (phi < 0) phi += 2.0 * kPi;
  return {w.x() * w.x() + w.y() * w.y(), phi / (2.0 * kPi)};
}

// Uniform point on a triangle, as barycentric weights (b0, b1) of its first two corners (square-root warp).
// pdf = 1 / area.
inline Eigen::Vector2d sample_uniform_triangle(double u1, double u2) {
  const double s = std::sqrt(u1);
  return {1.0 - s, u2 * s};
}
// Inverse of sample_uniform_triangle.
inline Eigen::Vector2d invert_uniform_triangle(const Eigen::Vector2d& b) {
  const double s = 1.0 - b.x();
  return {s * s, s > 0 ? b.y() / s : 0.0};
}

// An orthonormal frame (t, b, n) around unit n (Duff et al. 2017, branchless).
struct Frame {
  Vec3 t, b, n;
  explicit Frame(const Vec3& normal) : n(normal) {
    const double sign = std::copysign(1.0, n.z());
    const double a = -1.0 / (sign + n.z());
    const double c = n.x() * n.y() * a;
    t = Vec3(1.0 + sign * n.x() * n.x() * a, sign * c, -sign * n.x());
    b = Vec3(c, sign + n.y() * n.y() * a, -n.y());
  }
  Vec3 to_world(const Vec3& v) const { return v.x() * t + v.y() * b + v.z() * n; }
  Vec3 to_local(const Vec3& v) const { return {v.dot(t), v.dot(b), v.dot(n)}; }
};

}  // namespace radwalk
