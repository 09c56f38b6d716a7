#include "patch/contact_patches.h"

#include <algorithm>
#include <cmath>

namespace radwalk {
namespace {

// Whether x (in the plane of unit normal n) is strictly inside the convex polygon P, counter-clockwise about n,
// by more than eps from every side's line.
bool inside_convex(const std::vector<Vec3>& P, const Vec3& n, const Vec3& x, double eps) {
  const std::size_t m = P.size();
  for (std::size_t k = 0; k < m; ++k) {
    const Vec3 edge = P[(k + 1) % m] - P[k];
    const double length = edge.norm();
    if (!(length > 0)) continue;
    if (edge.cross(x - P[k]).dot(n) / length <= eps) return false;
  }
  return true;
}

// Whether x is inside the polygon P (any orientation, convex or not) projected along n: the crossing-number rule
// in the plane's own axes.
bool inside_polygon(const std::vector<Vec3>& P, const Vec3& n, const Vec3& x) {
  const Vec3 u = (std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized();
  const Vec3 v = n.cross(u);
  bool in = false;
  const std::size_t m = P.size();
  for (std::size_t k = 0, l = m - 1; k < m; l = k++) {
    const double xk = (P[k] - x).dot(u), yk = (P[k] - x).dot(v);
    const double xl = (P[l] - x).dot(u), yl = (P[l] - x).dot(v);
    if ((yk > 0) != (yl > 0) && xk + (0 - yk) * (xl - xk) / (yl - yk) > 0) in = !in;
  }
  return in;
}

}  // namespace

std::vector<ContactRegion> contact_regions(const Mesh& mesh, const std::vector<Contact>& contacts) {
  std::vector<ContactRegion> regions;
  for (const Contact& c : contacts) {
    const std::size_t m = c.footprint.size();
    if (m < 3 || !c.convex) continue;
    // The support's normal: the footprint runs counter-clockwise about it (Newell).
    Vec3 n = Vec3::Zero();
    for (std::size_t k = 0; k < m; ++k) n += c.footprint[k].cross(c.footprint[(k + 1) % m]);
    if (!(n.norm() > 0)) continue;
    ContactRegion r;
    r.normal = n.normalized();
    r.footprint = c.footprint;
    for (std::int32_t f : c.supports) {
      std::vector<Vec3> outline;
      for (int k = 0; k < (mesh.is_quad(std::size_t(f)) ? 4 : 3); ++k)
        outline.push_back(mesh.vertices[std::size_t(mesh.faces[std::size_t(f)][std::size_t(k)])]);
      r.supports.push_back(std::move(outline));
      r.support_faces.push_back(mesh.source_face(std::size_t(f)));
    }
    regions.push_back(std::move(r));
  }
  return regions;
}

std::vector<bool> contact_patches(const std::vector<ContactRegion>& regions, const PatchSet& patches) {
  std::vector<bool> in_contact(patches.size(), false);
  const double tol = kContactTolerance * std::max(patches.scene_extent(), 1e-300);
  for (const ContactRegion& r : regions) {
    const Vec3& n = r.normal;
    // The faces lying on the support back to back (bottoms), then the support's part under one of them.
    std::vector<std::size_t> support_part;
    std::vector<std::vector<Vec3>> bottoms;
    for (std::size_t i = 0; i < patches.size(); ++i) {
      const Vec3& x = patches.centroid[i];
      if (std::abs((x - r.footprint[0]).dot(n)) > tol || !inside_convex(r.footprint, n, x, tol)) continue;
      const double along = patches.normal[i].dot(n);
      if (along > 0.999 &&
          std::find(r.support_faces.begin(), r.support_faces.end(), patches.face[i]) != r.support_faces.end()) {
        support_part.push_back(i);
      } else if (along < -0.999 && std::any_of(r.supports.begin(), r.supports.end(), [&](const std::vector<Vec3>& s) {
                   return inside_polygon(s, n, x);
                 })) {
        in_contact[i] = true;
        std::vector<Vec3> outline;
        for (int k = 0; k < patches.corner_count(i); ++k) outline.push_back(patches.corner(i, k));
        bottoms.push_back(std::move(outline));
      }
    }
    for (const std::size_t i : support_part)
      if (std::any_of(bottoms.begin(), bottoms.end(), [&](const std::vector<Vec3>& b) {
            return inside_polygon(b, n, patches.centroid[i]);
          }))
        in_contact[i] = true;
  }
  return in_contact;
}

}  // namespace radwalk
