#include "apps/scene_camera.h"

#include <cmath>
#include <filesystem>
#include <string>

#include "core/error.h"

namespace radwalk::app {
namespace {

void bounding_box(const PatchSet& patches, Vec3& lo, Vec3& hi) {
  lo = hi = patches.points.empty() ? Vec3::Zero() : patches.points[0];
  for (const Vec3& p : patches.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
}

}  // namespace

Camera scene_camera(const std::string& scene, const PatchSet& patches, const std::vector<double>& c) {
  if (c.size() == 10) {
    Camera cam;
    cam.position = Vec3(c[0], c[1], c[2]);
    cam.direction = Vec3(c[3], c[4], c[5]) - cam.position;
    cam.up = Vec3(c[6], c[7], c[8]);
    // The option is in degrees, so is its refusal (P13: it was reported in radians).
    if (!(c[9] > 0 && c[9] < 180))
      throw InputError("--camera: the vertical field of view must be in (0, 180) degrees, got " + number_text(c[9]));
    cam.vfov = c[9] * kPi / 180.0;
    return cam;
  }
  if (std::filesystem::path(scene).stem().string().rfind("cornell_box", 0) == 0) return Camera::cornell_box();
  Vec3 lo, hi;
  bounding_box(patches, lo, hi);
  const Vec3 center = 0.5 * (lo + hi);
  const double radius = 0.5 * (hi - lo).norm();
  Camera cam;
  cam.vfov = 40.0 * kPi / 180.0;
  cam.position = center - Vec3(0, 0, radius / std::tan(0.5 * cam.vfov) + 0.5 * (hi - lo).z());
  cam.direction = Vec3(0, 0, 1);
  cam.up = Vec3(0, 1, 0);
  return cam;
}

Vec3 camera_focal_point(const Camera& camera, const PatchSet& patches) {
  Vec3 lo, hi;
  bounding_box(patches, lo, hi);
  const Vec3 d = camera.direction.normalized();
  const double distance = std::max((0.5 * (lo + hi) - camera.position).dot(d), 1e-6 * (hi - lo).norm() + 1e-12);
  return camera.position + distance * d;
}

}  // namespace radwalk::app
