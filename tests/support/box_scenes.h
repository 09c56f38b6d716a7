#pragma once
// Closed boxes built with PatchBuilder (watertight, k x k quads per face), shared by the visibility and form-factor
// tests. unit_cube_room(1) is the geometry of the unit cube of reference_problems.h.
#include <array>

#include <string>

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

// The unit cube room (one inward patch a face, rho 0.5, the ceiling y = 1 emitting E = 1) with a box of side 0.2
// standing on its floor, 3 x 3 patches a face (60 patches): the room's faces have the box's patches, 0.067 wide,
// within their fluctuation points' spacing of 1/8 (solve/fluctuation_source.h's near field).
inline PatchSet room_with_box_on_floor() {
  PatchBuilder b;
  const int m = b.add_material("white", Rgb(0.5, 0.5, 0.5));
  add_box(b, Vec3(0, 0, 0), Vec3(1, 1, 1), 1, true, m);
  add_box(b, Vec3(0.4, 0, 0.4), Vec3(0.6, 0.2, 0.6), 3, false, m);
  PatchSet patches = b.build();
  for (std::size_t i = 0; i < patches.size(); ++i)
    patches.E[i] = patches.centroid[i].y() > 1 - 1e-9 ? Rgb(1, 1, 1) : Rgb(0, 0, 0);
  return patches;
}

// The closed box [0,1]^3, k x k inward patches per wall, and a thin square panel at x = 0.5 over y, z in
// [0.25, 0.75], m x m patches, its front facing -x. Materials: 0 the walls, 1 the wall x = 0, 2 the wall x = 1,
// 3 the panel (two-sided when panel_two_sided); then add_back_sides(patches, all_two_sided).
inline PatchSet panel_box(int k, int m, const Material& walls, const Material& low, const Material& high, Material panel,
                   bool panel_two_sided, bool all_two_sided = false) {
  PatchBuilder b;
  b.add_material(walls);
  b.add_material(low);
  b.add_material(high);
  panel.two_sided = panel_two_sided;
  b.add_material(panel);
  add_box(b, Vec3(0, 0, 0), Vec3(1, 1, 1), k, true, 0);
  for (int a = 0; a < m; ++a)
    for (int c = 0; c < m; ++c) {
      const double y0 = 0.25 + 0.5 * a / m, y1 = 0.25 + 0.5 * (a + 1) / m;
      const double z0 = 0.25 + 0.5 * c / m, z1 = 0.25 + 0.5 * (c + 1) / m;
      b.add_quad(Vec3(0.5, y0, z0), Vec3(0.5, y0, z1), Vec3(0.5, y1, z1), Vec3(0.5, y1, z0), 3);
    }
  PatchSet ps = b.build();
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.material[i] != 0) continue;
    if (ps.centroid[i].x() < 1e-9) ps.material[i] = 1;
    if (ps.centroid[i].x() > 1 - 1e-9) ps.material[i] = 2;
  }
  set_radiometry_from_materials(ps);
  add_back_sides(ps, all_two_sided);
  return ps;
}

inline Material diffuse_material(const std::string& name, double rho, double Le = 0) {
  Material m;
  m.name = name;
  m.Kd = Rgb::Constant(rho);
  m.Ke = Rgb::Constant(Le);
  return m;
}

}  // namespace radwalk::test
