#pragma once
// The inside of an exact sphere, cut into latitude-longitude patches, for the path tracer's tests (test-only).
//
// Sphere of centre c and radius R; the front of every patch faces the centre (inward normal n(x) = (c - x) / R).
// Patches: n_z bands of equal height in z = (x - c).z / R (from -1 to 1) times n_phi sectors of equal angle, so
// each patch has the same area A_i = 4 pi R^2 / (n_z n_phi) (Archimedes: area on a sphere is uniform in z and
// phi), and a uniform point on a patch is (z, phi) uniform in its box. Emitters are whole top bands (a cap).
//
// Why a sphere: from any point x inside, the form factor to a surface element dA_y is
//   cos_x cos_y / (pi |x - y|^2) dA_y = dA_y / (4 pi R^2)      (cos_x = cos_y = |x - y| / (2R)),
// the same for every x. So with uniform rho every wall point receives the same irradiance
//   E_irr = Phi_e / ((1 - rho) A),   Phi_e = sum_i A_i E_i (emitted power), A = 4 pi R^2,
// and has radiosity B(x) = E(x) + rho E_irr exactly: no discretisation error. A polyhedral sphere has none of
// this (points on a facet see their neighbours at varying angles), hence the curved geometry.
//
// SphereScene bundles the PatchSet (exact areas; normals and centroids at the patch centres; corners on the
// sphere, for reference only), the SurfaceGeometry (true normals, exact uniform sampling, rays leaving off the
// surface by eps = 1e-9 R) and the Visibility (exact ray-sphere intersection).
#include <memory>

#include "patch/patch_set.h"
#include "pathtrace/surface_geometry.h"
#include "visibility/visibility.h"

namespace radwalk::test {

struct SphereCells {
  Vec3 centre = Vec3::Zero();
  double radius = 1;
  int n_z = 8;     // bands in z
  int n_phi = 16;  // sectors in phi
  PatchIndex index(int band, int sector) const { return band * n_phi + sector; }
  // The patch holding the point x on the sphere.
  PatchIndex locate(const Vec3& x) const;
  // A point of patch i from its (z, phi) box: (z, phi) = (z0 + a dz, (sector + b) dphi), a, b in [0, 1].
  Vec3 point(PatchIndex i, double a, double b) const;
};

// SphereGeometry and SphereVisibility keep a reference to their cells (which must outlive them).
class SphereGeometry final : public SurfaceGeometry {
 public:
  explicit SphereGeometry(const SphereCells& cells) : cells_(cells) {}
  Vec3 normal(PatchIndex i, const Vec3& x) const override;
  Vec3 sample_point(PatchIndex i, double u1, double u2) const override { return cells_.point(i, u1, u2); }
  Ray spawn_ray(PatchIndex i, const Vec3& x, const Vec3& d) const override;
  bool sees_itself(PatchIndex) const override { return true; }

 private:
  const SphereCells& cells_;
};

class SphereVisibility final : public Visibility {
 public:
  explicit SphereVisibility(const SphereCells& cells) : cells_(cells) {}
  Hit intersect(const Ray& ray) const override;
  bool occluded(const Ray& ray) const override { return intersect(ray).t < ray.tmax; }

 private:
  const SphereCells& cells_;
};

struct SphereScene {
  SphereCells cells;
  PatchSet patches;
  SphereGeometry geometry;
  SphereVisibility visibility;
  explicit SphereScene(const SphereCells& c) : cells(c), geometry(cells), visibility(cells) {}
};

// The inside of a sphere with reflectance rho everywhere and emission E on the top `emitting_bands` bands.
std::unique_ptr<SphereScene> make_sphere_scene(const SphereCells& cells, const Rgb& rho, const Rgb& E,
                                               int emitting_bands);

}  // namespace radwalk::test
