#pragma once
// Closed boxes built with PatchBuilder (watertight, k x k quads per face), shared by the visibility and form-factor
// tests. unit_cube_room(1) is the geometry of the unit cube of reference_problems.h.
#include <array>

#include "patch/patch_builder.h"

namespace radwalk::test {

// Adds the six faces of the box [lo, hi], each cut into k x k quads (normals inward when `inward`). Shared edges
// are watertight: every coordinate is a function of (axis, grid index) only, so neighbouring faces agree bit for
// bit. With `with_triangles`, every other quad is split into two triangles along its (0, 2) diagonal.
inline void add_box(PatchBuilder& b, const Vec3& lo, const Vec3& hi, int k, bool inward, int material,
                    bool with_triangles = false) {
  auto coord = [&](int axis, int g) { return g == k ? hi[axis] : lo[axis] + (hi[axis] - lo[axis]) * g / k; };
  for (int f = 0; f < 3; ++f)
    for (int side = 0; side < 2; ++side) {
      const int u = (f + 1) % 3, v = (f + 2) % 3;
      // Corner order (a,b), (a+1,b), (a+1,b+1), (a,b+1) has normal +e_f; inward at lo, reversed at hi.
      const bool reverse = (side == 1) == inward;
      for (int a = 0; a < k; ++a)
        for (int c = 0; c < k; ++c) {
          std::array<Vec3, 4> q;
          const int da[4] = {0, 1, 1, 0}, dc[4] = {0, 0, 1, 1};
          for (int r = 0; r < 4; ++r) {
            Vec3 p;
            p[f] = side ? hi[f] : lo[f];
            p[u] = coord(u, a + da[r]);
            p[v] = coord(v, c + dc[r]);
            q[reverse ? 3 - r : r] = p;
          }
          if (with_triangles && (a + c) % 2 == 0) {
            b.add_triangle(q[0], q[1], q[2], material);
            b.add_triangle(q[0], q[2], q[3], material);
          } else {
            b.add_quad(q[0], q[1], q[2], q[3], material);
          }
        }
    }
}

// The unit cube [0,1]^3 as a closed room: k x k patches per face, normals inward. With k = 1, patch order is
// x=0, x=1, y=0, y=1, z=0, z=1.
inline PatchSet unit_cube_room(int k, bool with_triangles = false) {
  PatchBuilder b;
  const int m = b.add_material("white", Rgb(0.5, 0.5, 0.5));
  add_box(b, Vec3(0, 0, 0), Vec3(1, 1, 1), k, true, m, with_triangles);
  return b.build();
}

}  // namespace radwalk::test
