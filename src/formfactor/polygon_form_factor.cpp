#include "formfactor/polygon_form_factor.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace radwalk {
namespace {

// Gauss-Legendre rules on [0, 1]: nodes and weights (Newton iteration on P_n), computed once.
template <int n>
struct GaussRule {
  std::array<double, n> x{}, w{};
  GaussRule() {
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
};
const GaussRule<10>& layer_rule() {
  static const GaussRule<10> rule;
  return rule;
}
const GaussRule<16>& smooth_rule() {
  static const GaussRule<16> rule;
  return rule;
}

// G1(w; h) = int_0^w ln sqrt(v^2 + h^2) dv + const = (w / 2) ln(w^2 + h^2) - w + h atan(w / h)  (h >= 0; the
// limits at h = 0 and at w = h = 0 taken).
double G1(double w, double h) {
  const double q = w * w + h * h;
  if (!(q > 0)) return 0.0;
  return 0.5 * w * std::log(q) - w + (h > 0 ? h * std::atan(w / h) : 0.0);
}

// G2(w; h) with G2'' = ln sqrt(w^2 + h^2): (1/4)(w^2 - h^2) ln(w^2 + h^2) - (3/4) w^2 + h w atan(w / h).
double G2(double w, double h) {
  const double q = w * w + h * h;
  if (!(q > 0)) return 0.0;
  return 0.25 * (w * w - h * h) * std::log(q) - 0.75 * w * w + (h > 0 ? h * w * std::atan(w / h) : 0.0);
}

// int_0^L ln |p - t v| dt for the point p (relative to the segment's start) and the segment t v, |v| = 1.
double segment_log_integral(const Vec3& p, const Vec3& v, double L) {
  const double tau = p.dot(v);
  const double h = std::sqrt(std::max(0.0, p.squaredNorm() - tau * tau));
  return G1(L - tau, h) - G1(-tau, h);
}

// The parameter s in [0, L1] of the point of segment a + s u nearest to segment b + t v (t in [0, L2]), and the
// distance; a few alternations of the two projections suffice for the grading below (it needs the neighbourhood,
// not the exact point), followed by the end-point checks.
void nearest_parameter(const Vec3& a, const Vec3& u, double L1, const Vec3& b, const Vec3& v, double L2, double& s,
                       double& dist) {
  const Vec3 d = a - b;
  const double uv = u.dot(v), du = d.dot(u), dv = d.dot(v), den = 1 - uv * uv;
  double sc = 0, tc = 0;
  if (den > 1e-14) {
    sc = std::clamp((uv * dv - du) / den, 0.0, L1);
  }
  // Alternate projections onto the two segments (exact for the clamped cases after two rounds).
  for (int k = 0; k < 3; ++k) {
    tc = std::clamp((d + sc * u).dot(v), 0.0, L2);
    sc = std::clamp((b + tc * v - a).dot(u), 0.0, L1);
  }
  s = sc;
  dist = (a + sc * u - b - tc * v).norm();
  // The end points of e against f, in case the alternation stopped at a worse local answer.
  for (double se : {0.0, L1}) {
    const double t = std::clamp((d + se * u).dot(v), 0.0, L2);
    const double r = (a + se * u - b - t * v).norm();
    if (r < dist) dist = r, s = se;
  }
}

// Closed form for parallel segments a + s u (s in [0, L1]) and b + t sigma u (t in [0, L2]):
// int int ln sqrt(w^2 + h^2) ds dt with w = c + s - sigma t, c = (a - b) . u, h the distance between the lines.
double parallel_log_integral(const Vec3& a, const Vec3& u, double L1, const Vec3& b, double sigma, double L2) {
  const Vec3 d = a - b;
  const double c = d.dot(u);
  const double h = std::sqrt(std::max(0.0, d.squaredNorm() - c * c));
  if (sigma > 0)  // w from c + s down to c + s - L2
    return G2(c + L1, h) - G2(c, h) - G2(c + L1 - L2, h) + G2(c - L2, h);
  return G2(c + L1 + L2, h) - G2(c + L2, h) - G2(c + L1, h) + G2(c, h);  // w = c + s + t
}

// Gauss-Legendre on [0, 1] with n points, 2 <= n <= 8 (the far-field rule below).
void gauss_rule(int n, const double*& x, const double*& w) {
  static const GaussRule<2> g2;
  static const GaussRule<3> g3;
  static const GaussRule<4> g4;
  static const GaussRule<5> g5;
  static const GaussRule<6> g6;
  static const GaussRule<7> g7;
  static const GaussRule<8> g8;
  switch (n) {
    case 2: x = g2.x.data(), w = g2.w.data(); return;
    case 3: x = g3.x.data(), w = g3.w.data(); return;
    case 4: x = g4.x.data(), w = g4.w.data(); return;
    case 5: x = g5.x.data(), w = g5.w.data(); return;
    case 6: x = g6.x.data(), w = g6.w.data(); return;
    case 7: x = g7.x.data(), w = g7.w.data(); return;
    default: x = g8.x.data(), w = g8.w.data(); return;
  }
}

// Quadrature points of a convex polygon for the far-field rule: a quadrilateral by the bilinear map of [0, 1]^2
// (n x n Gauss points, weight |x_u x x_v|), any other polygon as a fan of triangles from corner 0, each by the
// collapsed square x = c_0 + u (c_k - c_0) + u v (c_{k+1} - c_k) (weight 2 area u). Both maps are polynomial, so
// the integrand stays analytic in (u, v) and the Gauss rule keeps its rate. Returns the number of points.
int polygon_points(const Vec3* p, int count, int n, Vec3* x_out, double* w_out) {
  const double *gx, *gw;
  gauss_rule(n, gx, gw);
  int m = 0;
  if (count == 4) {
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) {
        const double u = gx[a], v = gx[b];
        const Vec3 xu = (1 - v) * (p[1] - p[0]) + v * (p[2] - p[3]);
        const Vec3 xv = (1 - u) * (p[3] - p[0]) + u * (p[2] - p[1]);
        x_out[m] = (1 - u) * (1 - v) * p[0] + u * (1 - v) * p[1] + u * v * p[2] + (1 - u) * v * p[3];
        w_out[m++] = gw[a] * gw[b] * xu.cross(xv).norm();
      }
    return m;
  }
  for (int k = 1; k + 1 < count; ++k) {
    const double twice_area = (p[k] - p[0]).cross(p[k + 1] - p[0]).norm();
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) {
        const double u = gx[a], v = gx[b];
        x_out[m] = p[0] + u * (p[k] - p[0]) + u * v * (p[k + 1] - p[k]);
        w_out[m++] = gw[a] * gw[b] * twice_area * u;
      }
  }
  return m;
}

}  // namespace

FarFieldRule far_field_rule(const Vec3* p, int np, const Vec3* q, int nq) {
  Vec3 cp = Vec3::Zero(), cq = Vec3::Zero();
  for (int k = 0; k < np; ++k) cp += p[k];
  for (int k = 0; k < nq; ++k) cq += q[k];
  cp /= double(np);
  cq /= double(nq);
  double rp = 0, rq = 0;
  for (int k = 0; k < np; ++k) rp = std::max(rp, (p[k] - cp).norm());
  for (int k = 0; k < nq; ++k) rq = std::max(rq, (q[k] - cq).norm());
  FarFieldRule rule;
  const double size = std::max(rp, rq);
  if (!(size > 0)) return rule;
  rule.ratio = ((cp - cq).norm() - rp - rq) / size;
  if (!(rule.ratio >= kFarFieldRatio)) return rule;
  // Smallest n with ratio^(-2n) <= 1e-14 (the Gauss rate of an integrand analytic in the Bernstein ellipse of
  // parameter >= ratio), at least 2.
  rule.points = std::max(2, int(std::ceil(7.0 / std::log10(rule.ratio))));
  rule.points = std::min(rule.points, 8);
  return rule;
}

double far_field_exchange_area(const Vec3* p, int np, const Vec3& n_p, const Vec3* q, int nq, const Vec3& n_q,
                               int n) {
  constexpr int kMax = 8 * 8 * (kMaxPolygonCorners - 2);
  Vec3 xp[kMax], xq[kMax];
  double wp[kMax], wq[kMax];
  const int mp = polygon_points(p, np, n, xp, wp);
  const int mq = polygon_points(q, nq, n, xq, wq);
  double sum = 0;
  for (int a = 0; a < mp; ++a) {
    double inner = 0;
    for (int b = 0; b < mq; ++b) {
      const Vec3 d = xq[b] - xp[a];
      const double r2 = d.squaredNorm();
      const double cx = n_p.dot(d), cy = -n_q.dot(d);
      if (cx > 0 && cy > 0) inner += wq[b] * cx * cy / (r2 * r2);
    }
    sum += wp[a] * inner;
  }
  return sum / kPi;
}

int clip_polygon_to_front(const Vec3* p, int count, const Vec3& plane_point, const Vec3& plane_normal,
                          double tolerance, Vec3* out) {
  double dist[kMaxPolygonCorners];
  bool any_front = false;
  for (int k = 0; k < count; ++k) {
    double s = plane_normal.dot(p[k] - plane_point);
    if (std::abs(s) <= tolerance) s = 0;  // on the plane
    dist[k] = s;
    any_front = any_front || s > 0;
  }
  if (!any_front) return 0;
  int m = 0;
  for (int k = 0; k < count; ++k) {
    const int k1 = (k + 1) % count;
    const double da = dist[k], db = dist[k1];
    if (da >= 0) out[m++] = p[k];
    if ((da > 0 && db < 0) || (da < 0 && db > 0)) {
      const double t = da / (da - db);  // the crossing of the plane on edge k -> k1
      out[m++] = p[k] + t * (p[k1] - p[k]);
    }
  }
  return m >= 3 ? m : 0;
}

double edge_pair_log_integral(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1) {
  const Vec3 ea = a1 - a0, eb = b1 - b0;
  const double L1 = ea.norm(), L2 = eb.norm();
  if (!(L1 > 0) || !(L2 > 0)) return 0.0;
  const Vec3 u = ea / L1, v = eb / L2;
  const double uv = u.dot(v);
  if (uv == 0) return 0.0;
  const double sin2 = u.cross(v).squaredNorm();
  if (sin2 < 1e-24)  // parallel (angle below 1e-12): the closed form
    return uv * parallel_log_integral(a0, u, L1, b0, uv > 0 ? 1.0 : -1.0, L2);

  // Outer integral over e by Gauss-Legendre, inner over f in closed form.
  const auto f = [&](double s) { return segment_log_integral(a0 + s * u - b0, v, L2); };
  double s_near = 0, dist = 0;
  nearest_parameter(a0, u, L1, b0, v, L2, s_near, dist);
  double sum = 0;
  if (dist >= 0.5 * L1) {  // analytic in a Bernstein ellipse of parameter >= 1 + sqrt(2): 16 points, ~1e-13
    const auto& g = smooth_rule();
    for (int k = 0; k < 16; ++k) sum += g.w[k] * f(g.x[k] * L1);
    return uv * sum * L1;
  }
  // Graded: on each side of s_near, layers [s_near + l/2, s_near + l] halving l down to max(dist, 1e-15 L1), then
  // one interval [s_near, s_near + l]: each layer sees the singularity at two half-widths beyond its end (Bernstein
  // parameter 3 + sqrt(8): 10 points, error ~1e-15 of the layer).
  const auto& g = layer_rule();
  const double floor_width = std::max(dist, 1e-15 * L1);
  const auto interval = [&](double lo, double hi) {
    double s = 0;
    for (int k = 0; k < 10; ++k) s += g.w[k] * f(lo + g.x[k] * (hi - lo));
    return s * (hi - lo);
  };
  for (int side = 0; side < 2; ++side) {
    const double length = side == 0 ? s_near : L1 - s_near;
    if (!(length > 0)) continue;
    const double dir = side == 0 ? -1.0 : 1.0;
    double l = length;
    while (l > floor_width) {
      const double lo = s_near + dir * 0.5 * l, hi = s_near + dir * l;
      sum += interval(std::min(lo, hi), std::max(lo, hi));
      l *= 0.5;
    }
    const double end = s_near + dir * l;
    sum += interval(std::min(s_near, end), std::max(s_near, end));
  }
  return uv * sum;
}

double polygon_exchange_area(const Vec3* p, int np, const Vec3& n_p, const Vec3* q, int nq, const Vec3& n_q) {
  // Scale for the on-plane tolerance: the larger polygon's extent.
  double size = 0;
  for (int k = 0; k < np; ++k) size = std::max(size, (p[k] - p[0]).norm());
  for (int k = 0; k < nq; ++k) size = std::max(size, (q[k] - q[0]).norm());
  const double tol = 1e-12 * size;
  Vec3 P[kMaxPolygonCorners], Q[kMaxPolygonCorners];
  const int mp = clip_polygon_to_front(p, np, q[0], n_q, tol, P);
  if (mp == 0) return 0.0;
  const int mq = clip_polygon_to_front(q, nq, p[0], n_p, tol, Q);
  if (mq == 0) return 0.0;
  // Far apart (relative to their size) and wholly in front of each other: the far-field Gauss rule, free of the
  // contour terms' cancellation.
  if (mp == np && mq == nq) {
    const FarFieldRule rule = far_field_rule(P, mp, Q, mq);
    if (rule.points > 0) return far_field_exchange_area(P, mp, n_p, Q, mq, n_q, rule.points);
  }
  double sum = 0;
  for (int e = 0; e < mp; ++e)
    for (int f = 0; f < mq; ++f) sum += edge_pair_log_integral(P[e], P[(e + 1) % mp], Q[f], Q[(f + 1) % mq]);
  return std::max(0.0, sum / (2 * kPi));
}

double patch_exchange_area(const PatchSet& patches, std::size_t i, std::size_t j) {
  if (i > j) std::swap(i, j);
  Vec3 p[4], q[4];
  const int np = patches.corner_count(i), nq = patches.corner_count(j);
  for (int k = 0; k < np; ++k) p[k] = patches.corner(i, k);
  for (int k = 0; k < nq; ++k) q[k] = patches.corner(j, k);
  return polygon_exchange_area(p, np, patches.normal[i], q, nq, patches.normal[j]);
}

bool clip_patch_pair(const PatchSet& patches, std::size_t i, std::size_t j, ClippedPair& out) {
  Vec3 p[4], q[4];
  const int np = patches.corner_count(i), nq = patches.corner_count(j);
  double size = 0;
  for (int k = 0; k < np; ++k) p[k] = patches.corner(i, k), size = std::max(size, (p[k] - p[0]).norm());
  for (int k = 0; k < nq; ++k) q[k] = patches.corner(j, k), size = std::max(size, (q[k] - q[0]).norm());
  const double tol = 1e-12 * size;
  out.np = clip_polygon_to_front(p, np, q[0], patches.normal[j], tol, out.p);
  out.nq = out.np ? clip_polygon_to_front(q, nq, p[0], patches.normal[i], tol, out.q) : 0;
  return out.np > 0 && out.nq > 0;
}

}  // namespace radwalk
