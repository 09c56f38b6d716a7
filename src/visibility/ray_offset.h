#pragma once
// Spawning rays that leave a patch: a scale-aware origin offset so the ray neither hits its own patch nor leaks
// through an edge it shares with a neighbour, when traced in single precision (Embree).
//
// The origin is moved off the sampled point p on patch i by eps, the scene's ray epsilon (ray_epsilon):
//   o = p + eps * s * n_i + pull_i * (c_i - p),   pull_i = min(1, eps / d_i),
// with n_i the patch normal, s = sign(dot(direction, n_i)) (the side the ray leaves by), c_i the patch centroid and
// d_i the smallest distance from c_i to the line of an edge of patch i. The first term puts o strictly on the
// ray's side of the patch plane (no self-hit); the second shrinks the patch about its centroid so that a point on
// an edge moves at least eps away from that edge's line (and no point moves more than eps * r_i / d_i, r_i the
// largest centroid-corner distance). So at a concave corner o is inside the room by about eps from both walls and
// a ray aimed into the neighbouring wall hits it at t > 0 instead of slipping past its edge.
// eps = max(1e-6 * scene_extent, 8 * FLT_EPSILON * max |coordinate|): it dominates float rounding of the origin
// and of Embree's ray/triangle test (both relative to coordinate size), and is 1e-6 of the scene, so the bias in
// form factors (a ray start moved by eps) is of order 1e-6 relative.
// The ray's tmax is infinite; the caller may shorten it.
#include <algorithm>
#include <cstddef>

#include "patch/patch_set.h"
#include "visibility/visibility.h"

namespace radwalk {

// The origin offset eps of a patch set (length unit of the mesh). O(number of points): compute it once.
double ray_epsilon(const PatchSet& patches);

// The per-patch part of the offset (normal, centroid, pull_i), for loops that spawn many rays from one patch.
struct PatchRayOffset {
  Vec3 normal_eps;  // eps * n_i
  Vec3 centroid;
  double pull = 0;
};
PatchRayOffset patch_ray_offset(const PatchSet& patches, std::size_t patch, double eps);

// A ray leaving `point` (on the patch of `offset`) along unit `direction`. O(1), inline: it runs once per ray.
inline Ray spawn_ray(const PatchRayOffset& offset, const Vec3& point, const Vec3& direction) {
  Ray ray;
  // Off the plane on the side the ray leaves by, then towards the centroid.
  ray.origin = point + (direction.dot(offset.normal_eps) >= 0 ? offset.normal_eps : Vec3(-offset.normal_eps)) +
               offset.pull * (offset.centroid - point);
  ray.direction = direction;
  return ray;
}

// The ray (spawned towards a point at distance r from the point it left) as a segment that stops before the plane
// through plane_point with unit normal plane_normal, as the moved origin o sees that plane:
//   tmax = min(r, n.(plane_point - o) / n.direction) (1 - 1e-5) - margin.
// At grazing angles the offset moves the plane nearer than r; tmax <= 0 leaves nothing to test. For occlusion
// queries "is anything between the two points" that must not find the target's own surface (shadow rays).
inline Ray stop_before_plane(Ray ray, double r, const Vec3& plane_point, const Vec3& plane_normal, double margin) {
  const double t_plane = std::min(r, plane_normal.dot(plane_point - ray.origin) / plane_normal.dot(ray.direction));
  ray.tmax = t_plane * (1 - 1e-5) - margin;
  return ray;
}

// A ray leaving `point` (on patch `patch`) along unit `direction`, offset by `eps` = ray_epsilon(patches).
// O(corners of the patch): computes patch_ray_offset each time.
inline Ray spawn_ray(const PatchSet& patches, std::size_t patch, const Vec3& point, const Vec3& direction,
                     double eps) {
  return spawn_ray(patch_ray_offset(patches, patch, eps), point, direction);
}

}  // namespace radwalk
