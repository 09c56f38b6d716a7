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

// The patches' centroids in a uniform grid over their bounding box, about one cell per patch (cubic cells over the
// axes along which the centroids spread, at most 1024 a side), each cell's patches in ascending order (a counting
// sort). query(lo, hi) gives every patch whose centroid lies in the box [lo, hi], and the others of the cells the
// box touches: a superset that the exact tests then filter, in O(cells touched + patches in them).
class CentroidGrid {
 public:
  explicit CentroidGrid(const PatchSet& patches) {
    const std::size_t n = patches.size();
    if (n == 0) return;
    lo_ = hi_ = patches.centroid[0];
    for (const Vec3& x : patches.centroid) lo_ = lo_.cwiseMin(x), hi_ = hi_.cwiseMax(x);
    const Vec3 extent = hi_ - lo_;
    double volume = 1;
    int axes = 0;
    for (int a = 0; a < 3; ++a)
      if (extent[a] > 0) volume *= extent[a], ++axes;
    // The cell edge h: about n cells over the spread axes, then widened until at most 4 n + 8 cells (a thin axis
    // would otherwise make the others fine).
    double h = axes > 0 ? std::pow(volume / double(n), 1.0 / axes) : 1.0;
    if (!(h > 0 && std::isfinite(h))) h = std::max(extent.maxCoeff(), 1e-300);
    const auto cells_along = [&](int a) {
      return extent[a] > 0 ? long(std::clamp(std::ceil(extent[a] / h), 1.0, 1024.0)) : 1L;
    };
    while (double(cells_along(0)) * double(cells_along(1)) * double(cells_along(2)) > 4.0 * double(n) + 8) h *= 1.5;
    for (int a = 0; a < 3; ++a) {
      cells_[a] = cells_along(a);
      scale_[a] = extent[a] > 0 ? double(cells_[a]) / extent[a] : 0.0;
    }
    start_.assign(std::size_t(cells_[0] * cells_[1] * cells_[2]) + 1, 0);
    std::vector<std::size_t> cell(n);
    for (std::size_t i = 0; i < n; ++i) ++start_[(cell[i] = cell_of(patches.centroid[i])) + 1];
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    patch_.resize(n);
    std::vector<std::size_t> next(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) patch_[next[cell[i]]++] = i;
  }

  template <class Visit>
  void query(const Vec3& lo, const Vec3& hi, Visit&& visit) const {
    if (patch_.empty()) return;
    long from[3], to[3];
    for (int a = 0; a < 3; ++a) {
      if (!(hi[a] >= lo_[a] && lo[a] <= hi_[a])) return;  // the box misses every centroid (or is NaN)
      from[a] = index(lo[a], a);
      to[a] = index(hi[a], a);
    }
    for (long z = from[2]; z <= to[2]; ++z)
      for (long y = from[1]; y <= to[1]; ++y)
        for (long x = from[0]; x <= to[0]; ++x) {
          const std::size_t c = std::size_t((z * cells_[1] + y) * cells_[0] + x);
          for (std::size_t k = start_[c]; k < start_[c + 1]; ++k) visit(patch_[k]);
        }
  }

 private:
  long index(double x, int a) const {
    const double u = std::floor((x - lo_[a]) * scale_[a]);
    return long(std::clamp(u, 0.0, double(cells_[a] - 1)));
  }
  std::size_t cell_of(const Vec3& x) const {
    return std::size_t((index(x.z(), 2) * cells_[1] + index(x.y(), 1)) * cells_[0] + index(x.x(), 0));
  }

  Vec3 lo_ = Vec3::Zero(), hi_ = Vec3::Zero();
  long cells_[3] = {1, 1, 1};
  double scale_[3] = {0, 0, 0};
  std::vector<std::size_t> start_;  // cell c holds patch_[start_[c], start_[c + 1])
  std::vector<std::size_t> patch_;
};

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
  if (regions.empty()) return in_contact;
  const double tol = kContactTolerance * std::max(patches.scene_extent(), 1e-300);
  // A centroid that passes the tests below lies within tol of the support's plane and inside the footprint's
  // prism, so within the footprint's bounding box grown by tol on every axis; the grid's query box is grown by
  // more (4 tol and 1e-9 of the box's size against rounding), so that it holds every such patch: the candidates are
  // a superset, the same tests decide, in ascending order as before.
  const CentroidGrid grid(patches);
  std::vector<std::size_t> candidates;
  for (const ContactRegion& r : regions) {
    const Vec3& n = r.normal;
    Vec3 lo = r.footprint[0], hi = r.footprint[0];
    for (const Vec3& p : r.footprint) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    const double margin = 4 * tol + 1e-9 * (hi - lo).norm();
    candidates.clear();
    grid.query(lo - Vec3::Constant(margin), hi + Vec3::Constant(margin),
               [&](std::size_t i) { candidates.push_back(i); });
    std::sort(candidates.begin(), candidates.end());
    // The faces lying on the support back to back (bottoms), then the support's part under one of them.
    std::vector<std::size_t> support_part;
    std::vector<std::vector<Vec3>> bottoms;
    for (const std::size_t i : candidates) {
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
