#pragma once
// Small analytic scenes for the path tracer's tests (test-only helpers).
#include <functional>

#include "patch/patch_builder.h"

namespace radwalk::test {

// A closed box [0,sx] x [0,sy] x [0,sz], each face cut into k x k quads facing inward. material(face, a, b)
// gives the material of cell (a, b) of face 0..5 (x=0, x=sx, y=0, y=sy, z=0, z=sz).
inline PatchSet closed_box(const Vec3& size, int k, PatchBuilder& builder,
                           const std::function<int(int face, int a, int b)>& material) {
  const double sx = size.x(), sy = size.y(), sz = size.z();
  // Face frames: origin, edge u, edge v, with u x v pointing into the box.
  struct FaceFrame {
    Vec3 o, u, v;
  };
  const FaceFrame faces[6] = {
      {Vec3(0, 0, 0), Vec3(0, sy, 0), Vec3(0, 0, sz)},   // x = 0, normal +x
      {Vec3(sx, 0, 0), Vec3(0, 0, sz), Vec3(0, sy, 0)},  // x = sx, normal -x
      {Vec3(0, 0, 0), Vec3(0, 0, sz), Vec3(sx, 0, 0)},   // y = 0, normal +y
      {Vec3(0, sy, 0), Vec3(sx, 0, 0), Vec3(0, 0, sz)},  // y = sy, normal -y
      {Vec3(0, 0, 0), Vec3(sx, 0, 0), Vec3(0, sy, 0)},   // z = 0, normal +z
      {Vec3(0, 0, sz), Vec3(0, sy, 0), Vec3(sx, 0, 0)},  // z = sz, normal -z
  };
  for (int f = 0; f < 6; ++f) {
    const auto& F = faces[f];
    for (int a = 0; a < k; ++a)
      for (int b = 0; b < k; ++b) {
        const Vec3 p0 = F.o + (double(a) / k) * F.u + (double(b) / k) * F.v;
        const Vec3 du = F.u / k, dv = F.v / k;
        builder.add_quad(p0, p0 + du, p0 + du + dv, p0 + dv, material(f, a, b));
      }
  }
  return builder.build();
}

// Closed box with every patch emitting Le and reflecting rho (the furnace).
inline PatchSet furnace(const Rgb& rho, const Rgb& Le) {
  PatchBuilder b;
  const int m = b.add_material("furnace", rho, Le);
  return closed_box(Vec3(1, 1.3, 0.8), 2, b, [&](int, int, int) { return m; });
}

// Closed box, uniform rho, one emitting cell in the middle of the ceiling (which also reflects).
inline PatchSet lit_box(const Rgb& rho, const Rgb& Le) {
  PatchBuilder b;
  const int wall = b.add_material("wall", rho);
  const int lamp = b.add_material("lamp", rho, Le);
  return closed_box(Vec3(1, 0.8, 1.3), 3, b,
                    [&](int f, int a, int c) { return (f == 3 && a == 1 && c == 1) ? lamp : wall; });
}
// Emitted power per channel, sum_i A_i E_i (W).
inline Rgb emitted_power(const PatchSet& p) {
  Rgb power = Rgb::Zero();
  for (std::size_t i = 0; i < p.size(); ++i) power += p.area[i] * p.E[i];
  return power;
}

}  // namespace radwalk::test

namespace radwalk::test {

// An axis-aligned cube [lo, lo + s]^3 with outward-facing quads (an obstacle inside a room).
inline void add_cube_outward(PatchBuilder& b, const Vec3& lo, double s, int material) {
  const Vec3 X(s, 0, 0), Y(0, s, 0), Z(0, 0, s);
  b.add_quad(lo, lo + Z, lo + Y + Z, lo + Y, material);                  // x = lo, normal -x
  b.add_quad(lo + X, lo + X + Y, lo + X + Y + Z, lo + X + Z, material);  // x = hi, normal +x
  b.add_quad(lo, lo + X, lo + X + Z, lo + Z, material);                  // y = lo, normal -y
  b.add_quad(lo + Y, lo + Y + Z, lo + X + Y + Z, lo + X + Y, material);  // y = hi, normal +y
  b.add_quad(lo, lo + Y, lo + X + Y, lo + X, material);                  // z = lo, normal -z
  b.add_quad(lo + Z, lo + X + Z, lo + X + Y + Z, lo + Y + Z, material);  // z = hi, normal +z
}

}  // namespace radwalk::test
