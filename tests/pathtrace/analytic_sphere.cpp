#include "analytic_sphere.h"

#include <algorithm>
#include <cmath>

namespace radwalk::test {

PatchIndex SphereCells::locate(const Vec3& x) const {
  const Vec3 p = (x - centre) / radius;
  const double z = std::clamp(p.z(), -1.0, 1.0);
  double phi = std::atan2(p.y(), p.x());
  if (phi < 0) phi += 2 * kPi;
  const int band = std::clamp(static_cast<int>((z + 1) / 2 * n_z), 0, n_z - 1);
  const int sector = std::clamp(static_cast<int>(phi / (2 * kPi) * n_phi), 0, n_phi - 1);
  return index(band, sector);
}

Vec3 SphereCells::point(PatchIndex i, double a, double b) const {
  const int band = i / n_phi, sector = i % n_phi;
  const double z = -1 + 2 * (band + a) / n_z;
  const double phi = 2 * kPi * (sector + b) / n_phi;
  const double r = std::sqrt(std::max(0.0, 1 - z * z));
  return centre + radius * Vec3(r * std::cos(phi), r * std::sin(phi), z);
}

Vec3 SphereGeometry::normal(PatchIndex, const Vec3& x) const { return (cells_.centre - x).normalized(); }

Ray SphereGeometry::spawn_ray(PatchIndex i, const Vec3& x, const Vec3& d) const {
  const Vec3 n = normal(i, x);
  const double eps = 1e-9 * cells_.radius;
  Ray ray;
  ray.origin = x + (d.dot(n) >= 0 ? eps : -eps) * n;
  ray.direction = d;
  return ray;
}

Hit SphereVisibility::intersect(const Ray& ray) const {
  // |o + t d - c|^2 = R^2 with |d| = 1: t = -b -+ sqrt(b^2 - q), b = d.(o - c), q = |o - c|^2 - R^2.
  // From inside (q < 0) only the far root is positive; from outside the near root is the first hit.
  const Vec3 oc = ray.origin - cells_.centre;
  const double b = ray.direction.dot(oc);
  const double q = oc.squaredNorm() - cells_.radius * cells_.radius;
  const double disc = b * b - q;
  Hit hit;
  if (disc < 0) return hit;
  const double s = std::sqrt(disc);
  const double t = q < 0 ? -b + s : (-b - s > 0 ? -b - s : -b + s);
  if (!(t > 0) || t > ray.tmax) return hit;
  const Vec3 x = ray.origin + t * ray.direction;
  hit.patch = cells_.locate(x);
  hit.t = t;
  hit.front = ray.direction.dot(x - cells_.centre) > 0;  // arriving against the inward normal
  return hit;
}

std::unique_ptr<SphereScene> make_sphere_scene(const SphereCells& cells, const Rgb& rho, const Rgb& E,
                                               int emitting_bands) {
  auto scene = std::make_unique<SphereScene>(cells);
  PatchSet& p = scene->patches;
  p.source = "analytic sphere";
  const double area = 4 * kPi * cells.radius * cells.radius / (cells.n_z * cells.n_phi);
  // Corner points on the (z, phi) grid (patch 0's box stretched over the grid); the pole rows repeat one point.
  const auto grid = [&](int band, int sector) { return band * (cells.n_phi + 1) + sector; };
  for (int band = 0; band <= cells.n_z; ++band)
    for (int sector = 0; sector <= cells.n_phi; ++sector) p.points.push_back(cells.point(0, band, sector));
  for (int band = 0; band < cells.n_z; ++band)
    for (int sector = 0; sector < cells.n_phi; ++sector) {
      const PatchIndex i = cells.index(band, sector);
      p.corners.push_back({grid(band, sector), grid(band + 1, sector), grid(band + 1, sector + 1),
                           grid(band, sector + 1)});
      p.centroid.push_back(cells.point(i, 0.5, 0.5));
      p.normal.push_back(scene->geometry.normal(i, p.centroid.back()));
      p.area.push_back(area);
      p.rho.push_back(rho);
      p.E.push_back(band >= cells.n_z - emitting_bands ? E : Rgb::Zero());
      p.face.push_back(i);
      p.material.push_back(-1);  // Lambertian with rho
    }
  return scene;
}

}  // namespace radwalk::test
