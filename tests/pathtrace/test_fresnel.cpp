// Fresnel terms against closed-form facts (deterministic, exact up to rounding).
#include <catch2/catch.hpp>
#include <cmath>

#include "pathtrace/dielectric.h"
#include "pathtrace/fresnel.h"

using namespace radwalk;

TEST_CASE("dielectric Fresnel: normal incidence, Brewster angle, total internal reflection", "[fresnel]") {
  const double eta = 1.5;
  // Normal incidence: ((eta - 1) / (eta + 1))^2 from either side.
  CHECK(fresnel_dielectric(1.0, eta) == Approx(0.04).epsilon(1e-12));
  CHECK(fresnel_dielectric(-1.0, eta) == Approx(0.04).epsilon(1e-12));
  // Brewster angle tan(theta_B) = eta: r_p = 0, so F = r_s^2 / 2 with r_s = cos(theta_i - theta_t) form.
  const double tb = std::atan(eta), tt = kPi / 2 - tb;
  const double rs = -std::sin(tb - tt) / std::sin(tb + tt);
  CHECK(fresnel_dielectric(std::cos(tb), eta) == Approx(0.5 * rs * rs).epsilon(1e-12));
  // From the inside beyond the critical angle asin(1/eta): total internal reflection.
  const double tc = std::asin(1.0 / eta);
  CHECK(fresnel_dielectric(-std::cos(tc + 0.01), eta) == 1.0);
  CHECK(fresnel_dielectric(-std::cos(tc - 0.01), eta) < 1.0);
  // Grazing incidence from outside reflects everything.
  CHECK(fresnel_dielectric(0.0, eta) == Approx(1.0));
  // Reciprocity: the pair (theta_i outside, theta_t inside) has the same reflectance from both sides.
  for (double ti = 0.05; ti < 1.5; ti += 0.1) {
    const double tt2 = std::asin(std::sin(ti) / eta);
    CHECK(fresnel_dielectric(std::cos(ti), eta) == Approx(fresnel_dielectric(-std::cos(tt2), eta)).epsilon(1e-10));
  }
}

TEST_CASE("conductor Fresnel: k = 0 equals the dielectric, F0 round-trips, k -> infinity reflects all",
          "[fresnel]") {
  for (double c = 0.0; c <= 1.0; c += 0.05) {
    CHECK(fresnel_conductor(c, 1.7, 0.0) == Approx(fresnel_dielectric(c, 1.7)).margin(1e-12));
    CHECK(fresnel_conductor(c, 0.2, 1e6) == Approx(1.0).margin(1e-5));
  }
  // Normal incidence of a conductor: ((n-1)^2 + k^2) / ((n+1)^2 + k^2) (gold-like n = 0.47, k = 2.4).
  const double n = 0.47, k = 2.4;
  CHECK(fresnel_conductor(1.0, n, k) == Approx(((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k)));
  const Rgb F0(0.95, 0.64, 0.54);
  const ConductorIor ior = conductor_ior_from_f0(F0);
  const Rgb F = fresnel_conductor(1.0, ior.eta, ior.k);
  for (int c = 0; c < 3; ++c) CHECK(F[c] == Approx(F0[c]).epsilon(1e-12));
  // Schlick matches at the end points.
  CHECK((fresnel_schlick(1.0, F0) - F0).abs().maxCoeff() < 1e-15);
  CHECK((fresnel_schlick(0.0, F0) - 1.0).abs().maxCoeff() < 1e-15);
}

TEST_CASE("refraction obeys Snell's law and stays in the plane of incidence", "[fresnel]") {
  const double eta = 1.33;
  for (double t = 0.05; t < 1.55; t += 0.1) {
    const Vec3 wo(std::sin(t) * std::cos(0.7), std::sin(t) * std::sin(0.7), std::cos(t));
    const auto wt = refract_local(wo, eta);
    REQUIRE(wt);
    CHECK(wt->norm() == Approx(1.0));
    CHECK(wt->z() < 0);
    const double sin_t = std::sqrt(wt->x() * wt->x() + wt->y() * wt->y());
    CHECK(std::sin(t) == Approx(eta * sin_t).epsilon(1e-12));
    CHECK(wo.cross(*wt).z() == Approx(0).margin(1e-12));  // coplanar with the normal
    // Reversibility: refracting wt from the inside gives wo back.
    const auto back = refract_local(*wt, 1.0 / eta);
    REQUIRE(back);
    CHECK((*back - wo).norm() < 1e-12);
  }
  // Beyond the critical angle from inside: no refracted direction.
  const double tc = std::asin(1.0 / eta);
  const Vec3 inside(std::sin(tc + 0.02), 0, -std::cos(tc + 0.02));
  CHECK_FALSE(refract_local(inside, 1.0 / eta));
}
