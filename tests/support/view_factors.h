#pragma once
// Exact view factors for the form-factor tests: closed forms from docs/reference-data.md (Howell's catalogue:
// rectangles C-11 and C-14, coaxial disks) and the exact value for any two planar polygons that see each other
// unobstructed, by the contour-integral form
//   A_1 F_12 = (1 / 2 pi) oint_{C1} oint_{C2} ln r (dr_1 . dr_2)
// (Stokes' theorem applied twice to the double area integral; each contour runs counter-clockwise about its
// polygon's normal), evaluated edge pair by edge pair with Gauss-Legendre quadrature. The integrand is smooth when
// the polygons share no point, so the quadrature is accurate to about 1e-12 there; the test checks it against the
// closed form for parallel squares.
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/types.h"

namespace radwalk::test {

// C-11: parallel, directly opposed a x b rectangles at distance c.
inline double parallel_rectangles(double a, double b, double c) {
  const double X = a / c, Y = b / c;
  const double x2 = 1 + X * X, y2 = 1 + Y * Y;
  return 2 / (kPi * X * Y) *
         (std::log(std::sqrt(x2 * y2 / (x2 + Y * Y))) + X * std::sqrt(y2) * std::atan(X / std::sqrt(y2)) +
          Y * std::sqrt(x2) * std::atan(Y / std::sqrt(x2)) - X * std::atan(X) - Y * std::atan(Y));
}

// C-14: perpendicular rectangles sharing an edge of length l; surface 1 of width w, surface 2 of height h.
inline double perpendicular_rectangles(double l, double w, double h) {
  const double W = w / l, H = h / l, W2 = W * W, H2 = H * H, S = std::sqrt(H2 + W2);
  const double log_term = std::log((1 + W2) * (1 + H2) / (1 + W2 + H2)) +
                          W2 * std::log(W2 * (1 + W2 + H2) / ((1 + W2) * (W2 + H2))) +
                          H2 * std::log(H2 * (1 + W2 + H2) / ((1 + H2) * (W2 + H2)));
  return 1 / (kPi * W) * (W * std::atan(1 / W) + H * std::atan(1 / H) - S * std::atan(1 / S) + 0.25 * log_term);
}

// Coaxial parallel disks of radii r1, r2 at distance a: F(1 -> 2).
inline double coaxial_disks(double r1, double r2, double a) {
  const double R1 = r1 / a, R2 = r2 / a, S = 1 + (1 + R2 * R2) / (R1 * R1);
  return (S - std::sqrt(S * S - 4 * (r2 / r1) * (r2 / r1))) / 2;
}

// An axis-aligned rectangle of the unit cube's walls: the plane coordinate[axis] = plane, spanning lo..hi on the
// two other axes (lo[axis] = hi[axis] = plane), facing into the cube.
struct AxisRectangle {
  int axis;
  double plane;
  Vec3 lo, hi;
};

// Sum over the four end-point differences of intervals [p, q] (surface 1) and [r, s] (surface 2) along an axis on
// which the kernel is translation invariant: E = (1/2) [Phi(s - p) - Phi(r - p) - Phi(s - q) + Phi(r - q)], Phi(L)
// the exchange area of the two surfaces over the same interval of length |L| (Phi even, Phi(0) = 0).
template <class Phi>
double interval_superposition(double p, double q, double r, double s, Phi&& phi) {
  const auto f = [&](double L) { return L == 0 ? 0.0 : phi(std::abs(L)); };
  return 0.5 * (f(s - p) - f(r - p) - f(s - q) + f(r - q));
}

// A_1 F_12 for two axis-aligned rectangles of the unit cube's inward walls, from the closed forms C-11 and C-14
// only (superposition, Howell's view-factor algebra): opposite walls by the interval sums above in both axes with
// Psi(a, b) = a b C-11(a, b, c); perpendicular walls by the interval sums along the joint with
// Phi(L) = L Y C-14(L, Y, Z) and inclusion-exclusion over the distances from the joint [y0, y1] x [z0, z1];
// 0 on one wall. An independent reference for the contour integral (formfactor/polygon_form_factor.h).
inline double axis_rectangle_exchange_area(const AxisRectangle& r1, const AxisRectangle& r2) {
  if (r1.axis == r2.axis) {
    if (r1.plane == r2.plane) return 0.0;
    const double c = std::abs(r1.plane - r2.plane);
    const int u = (r1.axis + 1) % 3, v = (r1.axis + 2) % 3;
    const auto along_u = [&](double a) {
      return interval_superposition(r1.lo[v], r1.hi[v], r2.lo[v], r2.hi[v],
                                    [&](double b) { return a * b * parallel_rectangles(a, b, c); });
    };
    return interval_superposition(r1.lo[u], r1.hi[u], r2.lo[u], r2.hi[u], along_u);
  }
  const int t = 3 - r1.axis - r2.axis;
  // Distances from the joint: r1 spans axis r2.axis, measured from r2's plane; r2 spans r1.axis from r1's plane.
  const double y0 = std::abs(r1.lo[r2.axis] - r2.plane), y1 = std::abs(r1.hi[r2.axis] - r2.plane);
  const double z0 = std::abs(r2.lo[r1.axis] - r1.plane), z1 = std::abs(r2.hi[r1.axis] - r1.plane);
  const auto from_joint = [&](double Y, double Z) {
    if (Y == 0 || Z == 0) return 0.0;
    return interval_superposition(r1.lo[t], r1.hi[t], r2.lo[t], r2.hi[t],
                                  [&](double L) { return L * Y * perpendicular_rectangles(L, Y, Z); });
  };
  const double ya = std::min(y0, y1), yb = std::max(y0, y1), za = std::min(z0, z1), zb = std::max(z0, z1);
  return from_joint(yb, zb) - from_joint(ya, zb) - from_joint(yb, za) + from_joint(ya, za);
}

// Gauss-Legendre nodes and weights on [0, 1] (Newton iteration on P_n).
inline void gauss_legendre(int n, std::vector<double>& x, std::vector<double>& w) {
  x.resize(n);
  w.resize(n);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1);
      const double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-16) break;
    }
    x[i] = 0.5 * (1 - z);
    w[i] = 1 / ((1 - z * z) * dp * dp);
  }
}

// A_1 F_12 for polygons p1, p2 (corners counter-clockwise about their normals) that share no point and see each
// other unobstructed. `pieces` sub-segments per edge, `order` Gauss points per piece.
inline double polygon_exchange_area(const std::vector<Vec3>& p1, const std::vector<Vec3>& p2, int pieces = 2,
                                    int order = 16) {
  std::vector<double> gx, gw;
  gauss_legendre(order, gx, gw);
  double sum = 0;
  for (std::size_t e = 0; e < p1.size(); ++e)
    for (std::size_t f = 0; f < p2.size(); ++f) {
      const Vec3 a = p1[e], da = p1[(e + 1) % p1.size()] - a;
      const Vec3 b = p2[f], db = p2[(f + 1) % p2.size()] - b;
      const double dot = da.dot(db);
      if (dot == 0) continue;
      double s = 0;
      for (int pa = 0; pa < pieces; ++pa)
        for (int ia = 0; ia < order; ++ia) {
          const Vec3 x = a + ((pa + gx[ia]) / pieces) * da;
          for (int pb = 0; pb < pieces; ++pb)
            for (int ib = 0; ib < order; ++ib)
              s += gw[ia] * gw[ib] * std::log((x - b - ((pb + gx[ib]) / pieces) * db).norm());
        }
      sum += s * dot / (pieces * pieces);
    }
  return sum / (2 * kPi);
}

}  // namespace radwalk::test
