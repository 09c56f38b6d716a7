#pragma once
// A generated city block of many small faces, for the clustering benchmark (bench_clusters.cpp). Deterministic: the
// same scene for the same cell size (no random numbers; the heights follow a fixed pattern).
//
// 3 x 3 buildings with 20 m x 20 m footprints and 10 m streets on a ground of 70 m x 70 m, heights 12 to 36 m
// (rounded to whole storeys). Every facade is cut into storeys and columns of cells about `cell` metres wide; each
// cell is a 3 x 3 grid of quads whose middle one is a window (glass) and the other eight its frame (concrete); under
// every storey runs a ledge (its top, front and underside, cut per column) 0.1 cell deep. Roofs are cut into cells,
// the ground into squares of about 2 cells, none under a building. A sky panel (one quad at 100 m, facing down, over
// the whole ground and beyond) is the only emitter; light escapes between it and the ground (an open scene).
// Faces: about 1.8e5 / cell^2 (cell = 4.2 m: 10^4, 1.34 m: 10^5, 0.42 m: 10^6).
#include <algorithm>
#include <cmath>

#include "patch/patch_builder.h"

namespace radwalk::bench {

inline PatchSet city_block(double cell) {
  PatchBuilder b;
  const int ground = b.add_material("ground", Rgb(0.30, 0.30, 0.28));
  const int concrete = b.add_material("concrete", Rgb(0.60, 0.55, 0.50));
  const int glass = b.add_material("glass", Rgb(0.15, 0.18, 0.20));
  const int ledge = b.add_material("ledge", Rgb(0.70, 0.70, 0.70));
  const int roof = b.add_material("roof", Rgb(0.40, 0.35, 0.35));
  const int sky = b.add_material("sky", Rgb::Zero(), Rgb(1.0, 1.0, 1.2));
  const double W = 20, street = 10, size = 3 * W + 4 * street;
  // A quad o + a u + c v over [a0, a1] x [c0, c1], counter-clockwise about u x v.
  const auto quad = [&](const Vec3& o, const Vec3& u, const Vec3& v, double a0, double a1, double c0, double c1, int m) {
    b.add_quad(o + a0 * u + c0 * v, o + a1 * u + c0 * v, o + a1 * u + c1 * v, o + a0 * u + c1 * v, m);
  };
  const int cols = std::max(1, static_cast<int>(std::lround(W / cell)));
  const double cw = W / cols;  // the cell's width (and storey height)
  const int ground_div = std::max(1, static_cast<int>(std::lround(street / (2 * cell))));
  const double g = street / ground_div;  // ground squares; 20 m and 10 m are multiples of g
  const int heights[9] = {12, 24, 18, 30, 36, 15, 21, 27, 33};
  for (int bx = 0; bx < 3; ++bx)
    for (int by = 0; by < 3; ++by) {
      const double x0 = street + bx * (W + street), y0 = street + by * (W + street);
      const int storeys = std::max(1, static_cast<int>(std::lround(heights[3 * bx + by] / cw)));
      const double h = storeys * cw;
      // Facades: (origin, along, outward normal); along x up = outward normal, out x along = up.
      struct Facade {
        Vec3 o, along, out;
      };
      const Facade facades[4] = {{Vec3(x0, y0, 0), Vec3::UnitX(), -Vec3::UnitY()},
                                 {Vec3(x0 + W, y0, 0), Vec3::UnitY(), Vec3::UnitX()},
                                 {Vec3(x0 + W, y0 + W, 0), -Vec3::UnitX(), Vec3::UnitY()},
                                 {Vec3(x0, y0 + W, 0), -Vec3::UnitY(), -Vec3::UnitX()}};
      const Vec3 up = Vec3::UnitZ();
      const double t[4] = {0, 0.25, 0.75, 1};  // the window's frame
      const double depth = 0.1 * cw;
      for (const Facade& f : facades) {
        for (int s = 0; s < storeys; ++s)
          for (int c = 0; c < cols; ++c) {
            const Vec3 o = f.o + c * cw * f.along + s * cw * up;
            for (int i = 0; i < 3; ++i)
              for (int j = 0; j < 3; ++j)
                quad(o, cw * f.along, cw * up, t[i], t[i + 1], t[j], t[j + 1], i == 1 && j == 1 ? glass : concrete);
            if (s == 0) continue;
            // The ledge at the storey's foot: top (up), front (out), underside (down).
            const Vec3 lo = f.o + c * cw * f.along + s * cw * up;
            quad(lo, depth * f.out, cw * f.along, 0, 1, 0, 1, ledge);                    // out x along = up
            quad(lo + depth * f.out - 0.05 * cw * up, cw * f.along, 0.05 * cw * up, 0, 1, 0, 1, ledge);  // front
            quad(lo - 0.05 * cw * up, cw * f.along, depth * f.out, 0, 1, 0, 1, ledge);  // along x out = down
          }
      }
      for (int i = 0; i < cols; ++i)
        for (int j = 0; j < cols; ++j)
          quad(Vec3(x0, y0, h), Vec3::UnitX(), Vec3::UnitY(), i * cw, (i + 1) * cw, j * cw, (j + 1) * cw, roof);
    }
  const int n = static_cast<int>(std::lround(size / g));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double cx = (i + 0.5) * g, cy = (j + 0.5) * g;
      const auto inside = [&](double v) {
        const double r = std::fmod(v - street, W + street);
        return v > street && v < size - street && r > 0 && r < W;
      };
      if (inside(cx) && inside(cy)) continue;  // under a building
      quad(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), i * g, (i + 1) * g, j * g, (j + 1) * g, ground);
    }
  quad(Vec3(-20, -20, 100), Vec3::UnitY(), Vec3::UnitX(), 0, size + 40, 0, size + 40, sky);  // facing down
  return b.build();
}

}  // namespace radwalk::bench
