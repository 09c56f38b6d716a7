#pragma once
// PatchBuilder: makes a PatchSet directly from polygons, for tests, benchmarks and generated scenes.
// Every polygon gets its own corner points (no sharing); face index = patch index.
#include "patch/patch_set.h"

namespace radwalk {

class PatchBuilder {
 public:
  // Adds a material; rho = m.Kd, E = pi * m.Ke for patches that use it. Returns its index.
  int add_material(const Material& m);
  // Adds a diffuse material with reflectance rho and emitted radiance Le (so E = pi * Le).
  int add_material(const std::string& name, const Rgb& rho, const Rgb& Le = Rgb::Zero());
  // Corners counter-clockwise seen from the front (the normal side).
  PatchIndex add_triangle(const Vec3& a, const Vec3& b, const Vec3& c, int material);
  PatchIndex add_quad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, int material);
  // Computes geometry and returns the patches.
  PatchSet build() const;

 private:
  PatchSet set_;
};

}  // namespace radwalk
