#include "apps/view_camera.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/types.h"
#include "visibility/embree_visibility.h"

namespace radwalk::app {

Vec3 view_probe_direction(int k) {
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  const double z = 1.0 - (2.0 * k + 1.0) / kViewProbes;
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return Vec3(r * std::cos(golden * k), z, r * std::sin(golden * k));
}

ViewPoint view_camera(const std::string& scene, const PatchSet& patches) {
  ViewPoint view;
  if (std::filesystem::path(scene).filename().string().rfind("cornell_box", 0) == 0) {
    view.position = Vec3(278, 273, -800);
    view.focal_point = Vec3(278, 273, 0);
    view.view_angle_deg = 2.0 * std::atan(0.0125 / 0.035) * 180.0 / kPi;
    return view;
  }
  // The bounding box of the patches' corners.
  Vec3 lo = patches.points.empty() ? Vec3::Zero() : patches.points[0], hi = lo;
  for (const Vec3& p : patches.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Vec3 c = 0.5 * (lo + hi);
  view.focal_point = c;
  // Closed: every probe from c reaches the front of a patch.
  bool closed = patches.size() > 0;
  if (closed) {
    const EmbreeVisibility visibility(patches);
    for (int k = 0; k < kViewProbes && closed; ++k) {
      const Hit h = visibility.intersect(Ray{c, view_probe_direction(k)});
      closed = !h.missed() && h.front;
    }
  }
  if (closed) {
    view.position = Vec3(c.x(), c.y(), lo.z() + 0.05 * (hi.z() - lo.z()));
    view.view_angle_deg = 60;
    return view;
  }
  const double radius = 0.5 * (hi - lo).norm();
  view.position = c - Vec3(0, 0, radius / std::tan(20.0 * kPi / 180.0) + 0.5 * (hi.z() - lo.z()));
  view.view_angle_deg = 40;
  return view;
}

}  // namespace radwalk::app
