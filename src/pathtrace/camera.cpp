#include "pathtrace/camera.h"

#include <cmath>

#include "core/error.h"

namespace radwalk {

PinholeCamera::PinholeCamera(const Camera& camera, int width, int height)
    : width_(width), height_(height), position_(camera.position) {
  if (width <= 0 || height <= 0) throw InputError("camera: image size must be positive");
  if (!(camera.vfov > 0 && camera.vfov < kPi)) throw InputError("camera: vertical field of view must be in (0, pi)");
  if (!(camera.direction.norm() > 0)) throw InputError("camera: direction is zero");
  forward_ = camera.direction.normalized();
  right_ = forward_.cross(camera.up);
  if (!(right_.norm() > 1e-9 * camera.up.norm())) throw InputError("camera: up is parallel to the direction");
  right_.normalize();
  up_ = right_.cross(forward_);
  half_h_ = std::tan(0.5 * camera.vfov);
  half_w_ = half_h_ * static_cast<double>(width) / static_cast<double>(height);
}

Ray PinholeCamera::generate_ray(double fx, double fy) const {
  const double sx = (2.0 * fx / width_ - 1.0) * half_w_;
  const double sy = (1.0 - 2.0 * fy / height_) * half_h_;
  Ray ray;
  ray.origin = position_;
  ray.direction = (forward_ + sx * right_ + sy * up_).normalized();
  return ray;
}

std::optional<Eigen::Vector2d> PinholeCamera::project(const Vec3& point) const {
  const Vec3 d = point - position_;
  const double z = d.dot(forward_);
  if (!(z > 0)) return std::nullopt;
  const double sx = d.dot(right_) / z, sy = d.dot(up_) / z;
  const double fx = (sx / half_w_ + 1.0) * 0.5 * width_;
  const double fy = (1.0 - sy / half_h_) * 0.5 * height_;
  if (!(fx >= 0 && fx < width_ && fy >= 0 && fy < height_)) return std::nullopt;
  return Eigen::Vector2d(fx, fy);
}

double PinholeCamera::importance(const Vec3& direction) const {
  const double c = direction.normalized().dot(forward_);
  if (!(c > 0)) return 0.0;
  const double sx = direction.dot(right_) / direction.dot(forward_);
  const double sy = direction.dot(up_) / direction.dot(forward_);
  if (std::abs(sx) > half_w_ || std::abs(sy) > half_h_) return 0.0;
  const double a_pixel = (2.0 * half_w_ / width_) * (2.0 * half_h_ / height_);
  return 1.0 / (a_pixel * c * c * c * c);
}

}  // namespace radwalk
