#pragma once
// What the hierarchy's tests share: the furnace cube and Student's t critical value of their replicate t-tests.
#include "patch/patch_builder.h"
#include "support/box_scenes.h"

namespace radwalk::test {

// Student's t two-sided critical value at the level of the normal critical value z (Cornish-Fisher, nu >= 20).
inline double t_critical(double z, double nu) {
  const double z2 = z * z;
  return z + (z2 * z + z) / (4 * nu) + (5 * z2 * z2 * z + 16 * z2 * z + 3 * z) / (96 * nu * nu) +
         (3 * z2 * z2 * z2 * z + 19 * z2 * z2 * z + 17 * z2 * z - 15 * z) / (384 * nu * nu * nu);
}

// The closed unit cube (one inward face per wall) whose walls all reflect rho and emit radiance Le: the constant
// solution B = pi Le / (1 - rho) (every point sees the whole enclosure).
inline PatchSet furnace(double rho, double Le) {
  PatchBuilder b;
  const int m = b.add_material("glow", Rgb::Constant(rho), Rgb::Constant(Le));
  add_box(b, Vec3(0, 0, 0), Vec3(1, 1, 1), 1, true, m);
  return b.build();
}

}  // namespace radwalk::test
