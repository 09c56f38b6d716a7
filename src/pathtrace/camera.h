#pragma once
// Pinhole camera: rays through a virtual film at unit distance, box-filtered pixels.
//
// Film coordinates (fx, fy) are continuous pixel coordinates: fx in [0, width) from left to right, fy in
// [0, height) from top to bottom; pixel (px, py) covers [px, px+1) x [py, py+1). The ray through (fx, fy) is
//   d = normalize(forward + sx * right + sy * up'),  sx = (2 fx / width - 1) tan(vfov/2) aspect,
//                                                   sy = (1 - 2 fy / height) tan(vfov/2),
// with forward = direction, right = forward x up, up' = right x forward (all unit), aspect = width / height.
// A pixel's value is the mean radiance over its film square (measurement with importance W = 1 / (A_pixel
// cos^4 theta) per unit film area at distance 1, which a uniform film sample estimates with weight 1).
// The Cornell box camera (docs/reference-data.md, "The Cornell box"): position (278, 273, -800), direction +z,
// up +y, focal length 0.035, film 0.025: vfov = 2 atan(0.0125 / 0.035) = 39.3077 degrees.
#include <cmath>
#include <optional>

#include "core/types.h"
#include "visibility/visibility.h"

namespace radwalk {

struct Camera {
  Vec3 position = Vec3(0, 0, 0);
  Vec3 direction = Vec3(0, 0, 1);
  Vec3 up = Vec3(0, 1, 0);
  double vfov = 2.0 * std::atan(0.0125 / 0.035);  // vertical field of view, radians

  // Field of view of a film of height film_height behind a lens of focal length focal (same unit).
  static double vfov_from_focal_length(double focal, double film_height) {
    return 2.0 * std::atan(0.5 * film_height / focal);
  }
  static Camera cornell_box() { return {Vec3(278, 273, -800), Vec3(0, 0, 1), Vec3(0, 1, 0),
                                        vfov_from_focal_length(0.035, 0.025)}; }
};

class PinholeCamera {
 public:
  // Throws InputError for a zero direction, up parallel to direction, vfov outside (0, pi) or an empty image.
  PinholeCamera(const Camera& camera, int width, int height);
  int width() const { return width_; }
  int height() const { return height_; }
  // The ray through film point (fx, fy).
  Ray generate_ray(double fx, double fy) const;
  // Inverse: the film point a world point projects to, if it lies in front of the camera and on the film.
  std::optional<Eigen::Vector2d> project(const Vec3& point) const;
  // Importance W(d) = 1 / (A_pixel cos^4 theta) for a direction d through the film (0 otherwise), A_pixel the
  // area of one pixel on the film at unit distance, theta the angle to the forward axis: with respect to
  // projected solid angle, int_{pixel} W cos(theta) dw = 1. For splatting light paths.
  double importance(const Vec3& direction) const;
  const Vec3& position() const { return position_; }
  const Vec3& forward() const { return forward_; }

 private:
  int width_, height_;
  Vec3 position_, forward_, right_, up_;
  double half_w_, half_h_;  // tan(hfov/2), tan(vfov/2)
};

}  // namespace radwalk
