#pragma once
// PatchPointSampler: uniform points on one patch (pdf 1 / A_i), with the per-patch work (corners, the triangle
// split of a quad) done once, for loops that draw many points from one patch. sample_patch_point (patch_set.h)
// draws one point the same way, so both give the same point for the same (u1, u2).
//
// A quad is the triangles (a, b, c) and (a, c, d), chosen with probabilities p1 = area(a, b, c) / area and 1 - p1;
// u1 is rescaled to [0, 1) within the chosen triangle, then the square-root warp (sample_uniform_triangle):
//   x = (1 - s) a' + s u2 b' + (1 - (1 - s) - s u2) c',   s = sqrt(u1).
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "patch/patch_set.h"

namespace radwalk {

struct PatchPointSampler {
  Vec3 a, b, c, d;  // corners; d = c for a triangle
  double p1 = 1;    // probability of the first triangle (a, b, c)

  PatchPointSampler(const PatchSet& ps, std::size_t i)
      : a(ps.corner(i, 0)), b(ps.corner(i, 1)), c(ps.corner(i, 2)), d(ps.is_quad(i) ? ps.corner(i, 3) : c) {
    if (ps.is_quad(i)) {
      const double a1 = (b - a).cross(c - a).norm(), a2 = (c - a).cross(d - a).norm();
      p1 = a1 / (a1 + a2);
    }
  }

  // The point for u in [0, 1)^2.
  Vec3 point(double u1, double u2) const {
    constexpr double kBelowOne = 0x1.fffffffffffffp-1;
    const bool first = u1 < p1;
    u1 = first ? u1 / p1 : (u1 - p1) / (1.0 - p1);
    const double s = std::sqrt(std::min(u1, kBelowOne));
    const double w0 = 1.0 - s, w1 = u2 * s;
    return first ? Vec3(w0 * a + w1 * b + (1.0 - w0 - w1) * c) : Vec3(w0 * a + w1 * c + (1.0 - w0 - w1) * d);
  }
};

}  // namespace radwalk
