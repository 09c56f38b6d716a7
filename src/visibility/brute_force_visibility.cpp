#include "visibility/brute_force_visibility.h"

#include <cmath>

#include "patch/contact_pairs.h"

namespace radwalk {
namespace {

// Moller-Trumbore ray/triangle test, edges included; returns t or a negative number.
double intersect_triangle(const Vec3& a, const Vec3& b, const Vec3& c, const Ray& ray) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 p = ray.direction.cross(e2);
  const double det = e1.dot(p);
  if (det == 0.0) return -1;  // ray parallel to the plane (or degenerate triangle)
  const double inv = 1.0 / det;
  const Vec3 s = ray.origin - a;
  const double u = s.dot(p) * inv;
  if (u < 0.0 || u > 1.0) return -1;
  const Vec3 q = s.cross(e1);
  const double v = ray.direction.dot(q) * inv;
  if (v < 0.0 || u + v > 1.0) return -1;
  return e2.dot(q) * inv;
}

}  // namespace

std::optional<double> intersect_patch(const PatchSet& patches, std::size_t i, const Ray& ray) {
  const Vec3& a = patches.corner(i, 0);
  double t = intersect_triangle(a, patches.corner(i, 1), patches.corner(i, 2), ray);
  if (patches.is_quad(i) && !(t > 0 && t <= ray.tmax))
    t = intersect_triangle(a, patches.corner(i, 2), patches.corner(i, 3), ray);
  if (t > 0 && t <= ray.tmax) return t;
  return std::nullopt;
}

BruteForceVisibility::BruteForceVisibility(const PatchSet& patches)
    : patches_(patches), pair_(contact_pair_ids(patches)) {}

Hit BruteForceVisibility::intersect(const Ray& ray) const {
  Hit hit;
  for (std::size_t i = 0; i < patches_.size(); ++i) {
    // A two-sided face's patch is seen from its front only (the other side's patch takes the rest); a contact
    // pair's patch from its back only (its partner, on the same points, takes the ray at its back first).
    const bool front = ray.direction.dot(patches_.normal[i]) < 0;
    if (patches_.two_sided(i) && !front) continue;
    if (pair_[i] >= 0 && front) continue;
    const auto t = intersect_patch(patches_, i, ray);
    if (t && *t < hit.t) {
      hit.t = *t;
      hit.patch = PatchIndex(i);
    }
  }
  if (!hit.missed()) hit.front = ray.direction.dot(patches_.normal[hit.patch]) < 0;
  return hit;
}

bool BruteForceVisibility::occluded(const Ray& ray) const {
  for (std::size_t i = 0; i < patches_.size(); ++i) {
    const auto t = intersect_patch(patches_, i, ray);
    if (t && *t < ray.tmax) return true;
  }
  return false;
}

}  // namespace radwalk
