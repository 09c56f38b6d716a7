#include "apps/scene_camera.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>

#include "core/error.h"
#include "visibility/embree_visibility.h"
#include "visibility/ray_offset.h"

namespace radwalk::app {
namespace {

void bounding_box(const PatchSet& patches, Vec3& lo, Vec3& hi) {
  lo = hi = patches.points.empty() ? Vec3::Zero() : patches.points[0];
  for (const Vec3& p : patches.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
}

// Direction k of n on a Fibonacci sphere (uniform to within O(1/n)).
Vec3 probe_direction(int k, int n) {
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  const double z = 1.0 - (2.0 * k + 1.0) / n;
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return Vec3(r * std::cos(golden * k), z, r * std::sin(golden * k));  // y is the sphere's axis
}

Vec3 up_for(const Vec3& d) { return std::abs(d.normalized().y()) > 0.99 ? Vec3(0, 0, 1) : Vec3(0, 1, 0); }

// The probe hits from p, or none if a probe escapes or hits a back (p is not enclosed).
bool enclosed(const Visibility& v, const Vec3& p, std::vector<Hit>& hits) {
  hits.assign(kProbeRays, Hit{});
  for (int k = 0; k < kProbeRays; ++k) {
    hits[static_cast<std::size_t>(k)] = v.intersect(Ray{p, probe_direction(k, kProbeRays)});
    if (hits[static_cast<std::size_t>(k)].missed() || !hits[static_cast<std::size_t>(k)].front) return false;
  }
  return true;
}

// Unoccluded direct irradiance at x on patch i from the emitters' centroids (channel sum).
double direct_irradiance(const PatchSet& s, const Visibility& v, std::size_t i, const Vec3& x,
                         const std::vector<std::size_t>& emitters, double eps) {
  double E = 0;
  for (const std::size_t j : emitters) {
    const Vec3 d = s.centroid[j] - x;
    const double r2 = d.squaredNorm();
    if (!(r2 > 0)) continue;
    const Vec3 w = d / std::sqrt(r2);
    const double ci = s.normal[i].dot(w), cj = -s.normal[j].dot(w);
    if (ci <= 0 || cj <= 0) continue;
    Ray ray = spawn_ray(s, i, x, w, eps);
    ray.tmax = std::sqrt(r2) * (1 - 1e-6);
    if (v.occluded(ray)) continue;
    E += s.E[j].sum() * s.area[j] * ci * cj / (kPi * r2);
  }
  return E;
}

Camera inside_camera(const PatchSet& s, const Visibility& v, const Vec3& p, const std::vector<Hit>& hits) {
  Camera cam;
  cam.position = p;
  cam.vfov = 60.0 * kPi / 180.0;
  std::vector<std::size_t> emitters;
  for (std::size_t j = 0; j < s.size(); ++j)
    if ((s.E[j] > 0).any()) emitters.push_back(j);
  const double eps = ray_epsilon(s);
  std::vector<double> score(kProbeRays, 0.0);
  double total = 0;
  int longest = 0;
  for (int k = 0; k < kProbeRays; ++k) {
    const Hit& h = hits[static_cast<std::size_t>(k)];
    if (h.t > hits[static_cast<std::size_t>(longest)].t) longest = k;
    const auto i = static_cast<std::size_t>(h.patch);
    if ((s.E[i] > 0).any()) continue;  // the lit surfaces, not the lights themselves
    score[static_cast<std::size_t>(k)] = direct_irradiance(s, v, i, p + h.t * probe_direction(k, kProbeRays), emitters, eps);
    total += score[static_cast<std::size_t>(k)];
  }
  Vec3 best = probe_direction(longest, kProbeRays);
  if (total > 0) {
    // The direction whose cone of half-angle vfov / 2 holds the most lit probes.
    const double cos_half = std::cos(0.5 * cam.vfov);
    double best_sum = -1;
    for (int a = 0; a < kProbeRays; ++a) {
      const Vec3 d = probe_direction(a, kProbeRays);
      if (std::abs(d.y()) > 0.9) continue;  // keep the view off the poles (floor, ceiling) for a usable up
      double sum = 0;
      for (int b = 0; b < kProbeRays; ++b)
        if (d.dot(probe_direction(b, kProbeRays)) >= cos_half) sum += score[static_cast<std::size_t>(b)];
      if (sum > best_sum) {
        best_sum = sum;
        best = d;
      }
    }
  }
  cam.direction = best;
  cam.up = up_for(best);
  return cam;
}

// The objects in an enclosure: the non-emitting patches whose centroid lies on none of the bounding box's six
// planes (to 1e-6 of its diagonal), i.e. not on the room's floor, walls or ceiling.
std::vector<std::size_t> object_patches(const PatchSet& s, const Vec3& lo, const Vec3& hi) {
  const double tol = 1e-6 * (hi - lo).norm();
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if ((s.E[i] > 0).any()) continue;
    const Vec3& c = s.centroid[i];
    bool on_box = false;
    for (int a = 0; a < 3; ++a) on_box = on_box || std::abs(c[a] - lo[a]) <= tol || std::abs(c[a] - hi[a]) <= tol;
    if (!on_box) out.push_back(i);
  }
  return out;
}

// A camera inside the enclosure that frames the objects: it looks at their area-weighted centroid c with a 60
// degree field of view, from the candidate position that sees the most of them. The candidates are the points
// 0.8 of the way from p (enclosed) to each probe hit; a candidate's score is the number of sampled object patches
// (at most kObjectSamples, every k-th) whose centroid is in its image (square of half-angle vfov / 2) and whose
// front it sees unoccluded (the first hit towards the centroid is that patch, from the front). Ties keep the
// earlier probe. Returns false (cam untouched) when there are no objects or no candidate sees one.
bool frame_objects(const PatchSet& s, const Visibility& v, const Vec3& p, const std::vector<Hit>& hits,
                   const std::vector<std::size_t>& objects, Camera& cam) {
  constexpr std::size_t kObjectSamples = 256;
  if (objects.empty()) return false;
  Vec3 c = Vec3::Zero();
  double area = 0;
  for (const std::size_t i : objects) {
    c += s.area[i] * s.centroid[i];
    area += s.area[i];
  }
  if (!(area > 0)) return false;
  c /= area;
  const std::size_t stride = std::max<std::size_t>(1, objects.size() / kObjectSamples);
  const double vfov = 60.0 * kPi / 180.0, tan_half = std::tan(0.5 * vfov);
  int best_score = 0;
  for (int k = 0; k < kProbeRays; ++k) {
    const Vec3 q = p + 0.8 * hits[static_cast<std::size_t>(k)].t * probe_direction(k, kProbeRays);
    const Vec3 f = (c - q).normalized();
    const Vec3 up = up_for(f), r = f.cross(up).normalized(), u = r.cross(f);
    int score = 0;
    for (std::size_t n = 0; n < objects.size(); n += stride) {
      const std::size_t i = objects[n];
      const Vec3 d = s.centroid[i] - q;
      const double z = d.dot(f);
      if (!(z > 0) || std::abs(d.dot(r)) > z * tan_half || std::abs(d.dot(u)) > z * tan_half) continue;
      const Hit h = v.intersect(Ray{q, d.normalized()});
      if (!h.missed() && h.front && static_cast<std::size_t>(h.patch) == i) ++score;
    }
    if (score > best_score) {
      best_score = score;
      cam.position = q;
      cam.direction = f;
      cam.up = up;
      cam.vfov = vfov;
    }
  }
  return best_score > 0;
}

}  // namespace

SceneCamera fit_scene_camera(const std::string& scene, const PatchSet& patches, const std::vector<double>& c,
                             const Visibility* visibility) {
  if (c.size() == 10) {
    Camera cam;
    cam.position = Vec3(c[0], c[1], c[2]);
    cam.direction = Vec3(c[3], c[4], c[5]) - cam.position;
    cam.up = Vec3(c[6], c[7], c[8]);
    // The option is in degrees, so is its refusal (P13: it was reported in radians).
    if (!(c[9] > 0 && c[9] < 180))
      throw InputError("--camera: the vertical field of view must be in (0, 180) degrees, got " + number_text(c[9]));
    cam.vfov = c[9] * kPi / 180.0;
    return {cam, "option"};
  }
  if (std::filesystem::path(scene).stem().string().rfind("cornell_box", 0) == 0)
    return {Camera::cornell_box(), "cornell_box"};
  Vec3 lo, hi;
  bounding_box(patches, lo, hi);
  const Vec3 center = 0.5 * (lo + hi);
  // The scene built here when the caller has none: it lives to the end, through the outside view's probes.
  std::unique_ptr<EmbreeVisibility> own;
  if (patches.size() > 0 && !visibility) {
    own = std::make_unique<EmbreeVisibility>(patches);
    visibility = own.get();
  }
  if (patches.size() > 0) {
    std::vector<Hit> hits;
    const Vec3 q = 0.25 * (hi - lo);
    for (const Vec3& p : {center, Vec3(center + Vec3(q.x(), 0, 0)), Vec3(center - Vec3(q.x(), 0, 0)),
                          Vec3(center + Vec3(0, q.y(), 0)), Vec3(center - Vec3(0, q.y(), 0)),
                          Vec3(center + Vec3(0, 0, q.z())), Vec3(center - Vec3(0, 0, q.z()))})
      if (enclosed(*visibility, p, hits)) {
        Camera cam;
        if (frame_objects(patches, *visibility, p, hits, object_patches(patches, lo, hi), cam))
          return {cam, "inside"};
        return {inside_camera(patches, *visibility, p, hits), "inside"};
      }
  }
  // Outside: of the views along +z (first), the other axes and the diagonals, each framing the bounding box's
  // sphere, the one whose kOutsideProbes^2 pixel-centre rays hit the most fronts of patches (emitters twice).
  const double radius = 0.5 * (hi - lo).norm();
  Camera cam;
  cam.vfov = 40.0 * kPi / 180.0;
  auto view_from = [&](const Vec3& d) {
    Camera c2 = cam;
    c2.direction = d.normalized();
    c2.up = up_for(c2.direction);
    c2.position = center - (radius / std::tan(0.5 * cam.vfov) +
                            0.5 * (hi - lo).cwiseProduct(c2.direction).cwiseAbs().sum()) * c2.direction;
    return c2;
  };
  cam = view_from(Vec3(0, 0, 1));
  if (patches.size() > 0) {
    constexpr int n = 24;
    double best = -1;
    for (const Vec3& d : {Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, -1, 0), Vec3(0, 1, 0),
                          Vec3(1, -1, 1), Vec3(-1, -1, 1), Vec3(1, -1, -1), Vec3(-1, -1, -1), Vec3(1, 1, 1),
                          Vec3(-1, 1, 1), Vec3(1, 1, -1), Vec3(-1, 1, -1)}) {
      const Camera c2 = view_from(d);
      const PinholeCamera pinhole(c2, n, n);
      double seen = 0;
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const Hit h = visibility->intersect(pinhole.generate_ray(x + 0.5, y + 0.5));
          if (!h.missed() && h.front) seen += (patches.E[static_cast<std::size_t>(h.patch)] > 0).any() ? 2 : 1;
        }
      if (seen > best) {
        best = seen;
        cam = c2;
      }
    }
  }
  return {cam, "outside"};
}

Camera scene_camera(const std::string& scene, const PatchSet& patches, const std::vector<double>& camera) {
  return fit_scene_camera(scene, patches, camera).camera;
}

Vec3 camera_focal_point(const Camera& camera, const PatchSet& patches) {
  Vec3 lo, hi;
  bounding_box(patches, lo, hi);
  const Vec3 d = camera.direction.normalized();
  const double distance = std::max((0.5 * (lo + hi) - camera.position).dot(d), 0.25 * (hi - lo).norm() + 1e-12);
  return camera.position + distance * d;
}

ViewPoint view_point(const Camera& camera, const PatchSet& patches) {
  ViewPoint view;
  view.position = camera.position;
  view.focal_point = camera_focal_point(camera, patches);
  const Vec3 d = camera.direction.normalized();
  view.up = (camera.up - camera.up.dot(d) * d).normalized();
  view.view_angle_deg = camera.vfov * 180.0 / kPi;
  return view;
}

}  // namespace radwalk::app
