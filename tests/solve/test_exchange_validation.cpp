// Validations of the net-radiation method (docs/theory/net_radiation.md) on enclosures with closed forms, with the
// analytic and the traced form factors: a long duct of two parallel plates and two side walls against the 2D
// crossed-strings view factors and the resulting net heat, and concentric polygon spheres against
// q_1 = sigma (T_1^4 - T_2^4) / (1/eps_1 + (A_1/A_2)(1/eps_2 - 1)).
#include <catch2/catch.hpp>
#include <array>
#include <cmath>
#include <map>
#include <vector>

#include "formfactor/analytic_form_factors.h"
#include "formfactor/form_factors.h"
#include "patch/patch_builder.h"
#include "solve/net_radiation.h"
#include "support/statistics.h"
#include "visibility/embree_visibility.h"

using namespace radwalk;

namespace {

constexpr double sigma = kStefanBoltzmann;

// The duct [0, w] x [0, h] x [0, L] without end caps, each wall cut into `segments` quads along z, normals
// inward; patch order: wall-major, walls 0 (y = 0, plate 1), 1 (y = h, plate 2), 2 (x = 0), 3 (x = w).
PatchSet duct(double w, double h, double L, int segments) {
  PatchBuilder b;
  const int m = b.add_material("wall", Rgb(0.5, 0.5, 0.5));
  for (int wall = 0; wall < 4; ++wall)
    for (int k = 0; k < segments; ++k) {
      const double z0 = L * k / segments, z1 = L * (k + 1) / segments;
      switch (wall) {
        case 0: b.add_quad({0, 0, z0}, {0, 0, z1}, {w, 0, z1}, {w, 0, z0}, m); break;  // normal +y
        case 1: b.add_quad({0, h, z0}, {w, h, z0}, {w, h, z1}, {0, h, z1}, m); break;  // normal -y
        case 2: b.add_quad({0, 0, z0}, {0, h, z0}, {0, h, z1}, {0, 0, z1}, m); break;  // normal +x
        default: b.add_quad({w, 0, z0}, {w, 0, z1}, {w, h, z1}, {w, h, z0}, m); break;  // normal -x
      }
    }
  return b.build();
}

// sum_j F_ij over the patches of wall W (segments patches each).
double to_wall(const SparseF& F, std::size_t i, int W, int segments) {
  double s = 0;
  for (SparseF::InnerIterator it(F, Eigen::Index(i)); it; ++it)
    if (it.col() / segments == W) s += double(it.value());
  return s;
}

}  // namespace

TEST_CASE("validation: a long duct's middle section against the 2D crossed-strings view factors and net heat, "
          "analytic and traced", "[net_radiation][validation]") {
  // Plates 1 m wide, 0.5 m apart, side walls 0.5 m; 120 m long in 1 m segments. Crossed strings (infinite duct):
  //   F_12 = (2 sqrt(w^2 + h^2) - 2 h) / (2 w),   F_13 = F_14 = (w + h - sqrt(w^2 + h^2)) / (2 w).
  // The bound of the finite length: from a point of the middle segment, a direction whose axial component a
  // (tangent to the wall) reaches beyond the duct's end, d = 59.5 m away, before crossing the cross-section
  // (at most D = sqrt(w^2 + h^2) transversally) has |a| / sqrt(1 - a^2) > d / D; under the cosine-weighted
  // hemisphere sin^2(theta) is uniform and |a| <= sin(theta), so that fraction is at most 1 - c^2 with
  // c = d / sqrt(d^2 + D^2): eta = D^2 / (d^2 + D^2) = 3.5e-4. The finite duct's F to a wall is then in
  // [F_inf - eta, F_inf] (it only lacks the wall's part beyond the ends).
  const double w = 1, h = 0.5, L = 120;
  const int segments = 120;
  const std::size_t middle = 60;  // plate 1, z in [60, 61]
  const double D = std::hypot(w, h), d = 59.5;
  const double eta = D * D / (d * d + D * D);
  const double F12 = (2 * D - 2 * h) / (2 * w), F13 = (w + h - D) / (2 * w);
  const PatchSet patches = duct(w, h, L, segments);
  const EmbreeVisibility visibility(patches);
  const AnalyticFormFactors exact = analytic_form_factors(patches, visibility);
  const SparseF& F = exact.form_factors.F;
  const double a12 = to_wall(F, middle, 1, segments), a13 = to_wall(F, middle, 2, segments),
               a14 = to_wall(F, middle, 3, segments), a11 = to_wall(F, middle, 0, segments);
  INFO("analytic: F_12 " << a12 << " (2D " << F12 << "), F_13 " << a13 << ", F_14 " << a14 << " (2D " << F13
                         << "), bound " << eta);
  CHECK(a11 == 0.0);
  const double rounding = 1e-6;  // float storage of the entries, 120 of them summed
  for (double a : {a13, a14}) {
    CHECK(a <= F13 + rounding);
    CHECK(a >= F13 - eta - rounding);
  }
  CHECK(a12 <= F12 + rounding);
  CHECK(a12 >= F12 - eta - rounding);

  // Net heat with black walls (J = sigma T^4 exactly, so q = sigma T^4 - G and only F matters): the middle
  // section of plate 1 at 600 K against plate 2 at 300 K and the side walls at 450 K and 350 K, the ends open to
  // an ambient at 0 K. 2D: q_1 = sigma (T_1^4 - F_12 T_2^4 - F_13 (T_3^4 + T_4^4)). The finite duct lacks at most
  // eta of the irradiance from walls at most 600 K, so |q - q_2D| <= eta sigma 600^4 (and q >= q_2D).
  const double T[4] = {600, 300, 450, 350};
  NetRadiationInput in;
  in.area = patches.area;
  in.sky.resize(patches.size());
  for (std::size_t i = 0; i < patches.size(); ++i) {
    SurfaceCondition s;
    s.emissivity = 1;
    s.temperature = T[i / segments];
    in.surface.push_back(s);
    in.sky[i] = std::clamp(1 - double(F.row(Eigen::Index(i)).sum()), 0.0, 1.0);
  }
  const double q2D = sigma * (std::pow(T[0], 4) - F12 * std::pow(T[1], 4) -
                              F13 * (std::pow(T[2], 4) + std::pow(T[3], 4)));
  const double q_bound = eta * sigma * std::pow(600.0, 4) + 1e-6 * sigma * std::pow(600.0, 4);
  const NetRadiationResult r = net_radiation_result(in, F, dense_net_radiation(in, F));
  INFO("q of the middle section " << r.q[middle] << " W/m^2, 2D " << q2D << ", bound " << q_bound);
  CHECK(r.q[middle] >= q2D - 1e-6 * sigma * std::pow(600.0, 4));
  CHECK(r.q[middle] - q2D <= q_bound);

  // Traced (20000 rays per patch): the middle row's F to each wall, binomial standard error sqrt(F(1 - F)/n)
  // (stratified rays: at most that), within [F_inf - eta, F_inf] widened by z se; Sidak over the 3 walls,
  // family-wise alpha = 0.01.
  FormFactorOptions options;
  options.rays_per_patch = 20000;
  options.seed = 5;
  const FormFactors traced = estimate_form_factors(patches, visibility, options);
  const double z = z_critical(sidak(0.01, 3));
  const int walls[3] = {1, 2, 3};
  const double inf[3] = {F12, F13, F13};
  for (int k = 0; k < 3; ++k) {
    const double f = to_wall(traced.F, middle, walls[k], segments);
    const double se = std::sqrt(f * (1 - f) / 20000);
    INFO("traced F to wall " << walls[k] << ": " << f << " +- " << se << ", 2D " << inf[k]);
    CHECK(f <= inf[k] + z * se);
    CHECK(f >= inf[k] - eta - z * se);
  }
}

namespace {

// A sphere of radius r about the origin: the icosahedron with each triangle cut into 4 `levels` times, vertices
// projected onto the sphere; normals outward, or inward when `inward`. Shared midpoints are computed from the
// same two points in either order ((a + b) is commutative), so the mesh is watertight.
void add_sphere(PatchBuilder& b, double r, int levels, bool inward, int material) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<Vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                         {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (Vec3& p : v) p.normalize();
  std::vector<std::array<Vec3, 3>> tri;
  const int f[20][3] = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                        {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                        {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (const auto& k : f) tri.push_back({v[std::size_t(k[0])], v[std::size_t(k[1])], v[std::size_t(k[2])]});
  for (int level = 0; level < levels; ++level) {
    std::vector<std::array<Vec3, 3>> next;
    for (const auto& q : tri) {
      const Vec3 ab = (q[0] + q[1]).normalized(), bc = (q[1] + q[2]).normalized(), ca = (q[2] + q[0]).normalized();
      next.push_back({q[0], ab, ca});
      next.push_back({ab, q[1], bc});
      next.push_back({ca, bc, q[2]});
      next.push_back({ab, bc, ca});
    }
    tri = std::move(next);
  }
  for (const auto& q : tri) {
    // The icosahedron's faces above run counter-clockwise seen from outside.
    if (inward)
      b.add_triangle(r * q[0], r * q[2], r * q[1], material);
    else
      b.add_triangle(r * q[0], r * q[1], r * q[2], material);
  }
}

}  // namespace

TEST_CASE("validation: concentric polygon spheres against the two-surface closed form, traced",
          "[net_radiation][validation]") {
  // Inner sphere r = 1 (eps_1 = 0.6, 500 K), outer r = 2 (black, 300 K), 320 triangles each. With a black outer
  // surface J_2 = sigma T_2^4 on every patch, every inner patch (convex body: all its radiation reaches the outer
  // one, F_1->2 = 1 for any polygon discretisation) has G = sigma T_2^4 and
  //   q_1 = eps_1 sigma (T_1^4 - T_2^4) = sigma (T_1^4 - T_2^4) / (1/eps_1 + (A_1/A_2)(1/eps_2 - 1)),  eps_2 = 1:
  // the discretisation of the spheres changes nothing (bound 0) and the traced F only through the rows of the
  // inner patches, whose sums are exactly 1 when no ray escapes. So Q_1 = A_1 q_1 to rounding (1e-9 relative),
  // with A_1 the polygon area. With eps_2 < 1 the outer radiosity is not uniform on the polygon sphere and the
  // closed form holds within the bound of the next test case.
  PatchBuilder b;
  const int inner = b.add_material("inner", Rgb(0.5, 0.5, 0.5)), outer = b.add_material("outer", Rgb(0, 0, 0));
  add_sphere(b, 1, 2, false, inner);
  add_sphere(b, 2, 2, true, outer);
  const PatchSet patches = b.build();
  REQUIRE(patches.size() == 640);
  const EmbreeVisibility visibility(patches);
  FormFactorOptions options;
  options.rays_per_patch = 2000;
  options.seed = 11;
  const FormFactors ff = estimate_form_factors(patches, visibility, options);
  const double eps1 = 0.6, T1 = 500, T2 = 300;
  NetRadiationInput in;
  in.area = patches.area;
  in.sky.assign(patches.size(), 0.0);
  double A1 = 0, escaped = 0;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    SurfaceCondition s;
    const bool is_inner = i < 320;
    s.emissivity = is_inner ? eps1 : 1.0;
    s.temperature = is_inner ? T1 : T2;
    in.surface.push_back(s);
    if (is_inner) A1 += patches.area[i];
    escaped += ff.escaped[i] + ff.back_hits[i];
    in.sky[i] = double(ff.escaped[i]) / ff.rays[i];
  }
  REQUIRE(escaped == 0);
  const NetRadiationResult r = net_radiation_result(in, ff.F, dense_net_radiation(in, ff.F));
  double Q1 = 0;
  for (std::size_t i = 0; i < 320; ++i) Q1 += r.Q[i];
  const double closed = A1 * eps1 * sigma * (std::pow(T1, 4) - std::pow(T2, 4));
  INFO("Q_1 " << Q1 << " W, closed form " << closed << " W (A_1 = " << A1 << " m^2, sphere " << 4 * M_PI << ")");
  CHECK(std::abs(Q1 - closed) <= 1e-6 * closed);  // float rows: each sums to 1 within 1e-7
}

TEST_CASE("validation: concentric grey polygon spheres against the two-surface closed form within the stated "
          "discretisation bound, traced over 8 seeds", "[net_radiation][validation]") {
  // Inner icosphere r_1 = 1 (eps_1 = 0.6, 500 K), outer r_2 = 2 (eps_2 = 0.5, 300 K), 320 triangles each.
  //
  // The bound. The two-surface solution (J_1, J_2 uniform; the closed form with the polygon areas A_1, A_2)
  // satisfies every inner row of the patch system exactly (an inner row of F sums to 1, all to the outer patches)
  // and leaves in outer row k the residual r_k = -rho_2 (f_k - A_1/A_2)(J_1 - J_2), f_k = sum_{i inner} F_ki. So
  // the patch solution is J = J_uniform + delta with (I - diag(rho) F) delta = -r, and
  //   |delta|_inf <= rho_2 Df |J_1 - J_2| / (1 - max rho)         (|diag(rho) F|_inf <= max rho),
  //   |Q_1 - Q_1,closed| = (eps_1/rho_1) |sum_i A_i delta_i| <= (eps_1/rho_1) A_1 |delta|_inf,
  // with Df = max_k |f_k - A_1/A_2|. f_k is bracketed geometrically: the inner polyhedron lies between the balls
  // of radius r_in (its smallest face distance) and r_1; a triangle with vertices on the outer sphere has its
  // normal through the centre, so from a point of it at distance R (h_k <= R <= r_2, h_k its plane's distance) a
  // ball of radius a <= h_k has the point view factor (a/R)^2 cos(theta) = a^2 h_k / R^3; hence
  //   r_in^2 h_k / r_2^3 <= f_k <= r_1^2 / h_k^2.
  // The traced estimate: Q_1 over 8 seeds, its mean against the closed form within the bound plus
  // t_{0.995, 7} s / sqrt(8) (two-sided alpha = 0.01).
  PatchBuilder b;
  const int inner = b.add_material("inner", Rgb(0.5, 0.5, 0.5)), outer = b.add_material("outer", Rgb(0.5, 0.5, 0.5));
  const double r1 = 1, r2 = 2;
  add_sphere(b, r1, 2, false, inner);
  add_sphere(b, r2, 2, true, outer);
  const PatchSet patches = b.build();
  REQUIRE(patches.size() == 640);
  const double eps1 = 0.6, eps2 = 0.5, T1 = 500, T2 = 300, rho1 = 1 - eps1, rho2 = 1 - eps2;
  double A1 = 0, A2 = 0, r_in = r1, h_min = r2, h_max = 0;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const double h = std::abs(patches.normal[i].dot(patches.centroid[i]));
    if (i < 320) {
      A1 += patches.area[i];
      r_in = std::min(r_in, h);
    } else {
      A2 += patches.area[i];
      h_min = std::min(h_min, h);
      h_max = std::max(h_max, h);
    }
  }
  const double fbar = A1 / A2;
  const double Df = std::max({std::abs(r1 * r1 / (h_min * h_min) - fbar), std::abs(r_in * r_in * h_min / (r2 * r2 * r2) - fbar),
                              std::abs(r1 * r1 / (h_max * h_max) - fbar), std::abs(r_in * r_in * h_max / (r2 * r2 * r2) - fbar)});
  const double Eb1 = sigma * std::pow(T1, 4), Eb2 = sigma * std::pow(T2, 4);
  const double q1 = (Eb1 - Eb2) / (1 / eps1 + fbar * (1 / eps2 - 1));
  const double Q_closed = A1 * q1;
  const double J1 = Eb1 - q1 * rho1 / eps1, J2 = Eb2 + (Q_closed / A2) * rho2 / eps2;
  const double bound = (eps1 / rho1) * A1 * rho2 * Df * std::abs(J1 - J2) / (1 - std::max(rho1, rho2));

  const EmbreeVisibility visibility(patches);
  NetRadiationInput in;
  in.area = patches.area;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    SurfaceCondition s;
    s.emissivity = i < 320 ? eps1 : eps2;
    s.temperature = i < 320 ? T1 : T2;
    in.surface.push_back(s);
  }
  const int seeds = 8;
  double sum = 0, sum_sq = 0;
  for (int seed = 1; seed <= seeds; ++seed) {
    FormFactorOptions options;
    options.rays_per_patch = 2000;
    options.seed = std::uint64_t(seed);
    const FormFactors ff = estimate_form_factors(patches, visibility, options);
    double leaked = 0;
    for (std::size_t i = 0; i < patches.size(); ++i) leaked += ff.escaped[i] + ff.back_hits[i];
    REQUIRE(leaked == 0);
    const NetRadiationResult r = net_radiation_result(in, ff.F, dense_net_radiation(in, ff.F));
    double Q1 = 0;
    for (std::size_t i = 0; i < 320; ++i) Q1 += r.Q[i];
    sum += Q1;
    sum_sq += Q1 * Q1;
  }
  const double mean = sum / seeds, s = std::sqrt(std::max(0.0, (sum_sq - seeds * mean * mean) / (seeds - 1)));
  const double t = 3.4994832973;  // Student t, 7 degrees of freedom, upper 0.005 quantile (two-sided 0.01)
  INFO("Q_1 mean " << mean << " W (s " << s << " over " << seeds << " seeds), closed form " << Q_closed
                   << " W; bound " << bound << " W (Df " << Df << ", f_bar " << fbar << ", r_in " << r_in
                   << "), statistical " << t * s / std::sqrt(double(seeds)) << " W");
  CHECK(std::abs(mean - Q_closed) <= bound + t * s / std::sqrt(double(seeds)));
  // The bound is informative: well below the heat itself.
  CHECK(bound < 0.1 * Q_closed);
}
