// Sampling triplets: round trips and chi-square tests of each sampler against its pdf.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "core/rng.h"
#include "core/sampling.h"
#include "support/stat_checks.h"

using namespace radwalk;

TEST_CASE("cosine hemisphere: inverse round-trips and pdf integrates the samples", "[sampling]") {
  Rng rng = stream(1, StreamDomain::test, 2);
  for (int k = 0; k < 1000; ++k) {
    const double u1 = rng.uniform(), u2 = rng.uniform();
    const Vec3 w = sample_cosine_hemisphere(u1, u2);
    REQUIRE(w.norm() == Approx(1.0).epsilon(1e-12));
    const Eigen::Vector2d u = invert_cosine_hemisphere(w);
    CHECK(u.x() == Approx(u1).margin(1e-9));
    CHECK(u.y() == Approx(u2).margin(1e-9));
  }
}

TEST_CASE("cosine hemisphere samples follow cos(theta)/pi (chi-square, alpha 1e-4)", "[sampling][statistical]") {
  // Bins in (cos theta, phi); expected count = n * integral of the pdf over the bin = n * (c1^2 - c0^2) / nphi.
  const int nc = 16, nphi = 16, n = 400000;
  std::vector<double> obs(nc * nphi, 0), exp(nc * nphi, 0);
  Rng rng = stream(5, StreamDomain::test, 6);
  for (int k = 0; k < n; ++k) {
    const Vec3 w = sample_cosine_hemisphere(rng.uniform(), rng.uniform());
    const int ic = std::min(nc - 1, static_cast<int>(w.z() * nc));
    double phi = std::atan2(w.y(), w.x());
    if (phi < 0) phi += 2 * kPi;
    const int ip = std::min(nphi - 1, static_cast<int>(phi / (2 * kPi) * nphi));
    obs[ic * nphi + ip] += 1;
  }
  for (int ic = 0; ic < nc; ++ic) {
    const double c0 = double(ic) / nc, c1 = double(ic + 1) / nc;
    for (int ip = 0; ip < nphi; ++ip) exp[ic * nphi + ip] = n * (c1 * c1 - c0 * c0) / nphi;
  }
  test::check_chi_square("cosine hemisphere", obs, exp, 1e-4);
}

TEST_CASE("uniform triangle warp is uniform and round-trips", "[sampling][statistical]") {
  Rng rng = stream(9, StreamDomain::test, 9);
  const int g = 8, n = 200000;
  // Count samples in the g*g sub-triangles... simpler: in bins of barycentric (b0, b1) on a square grid
  // restricted to the triangle, expected count proportional to the bin's area inside the triangle.
  std::vector<double> obs(g * g, 0), exp(g * g, 0);
  for (int k = 0; k < n; ++k) {
    const double u1 = rng.uniform(), u2 = rng.uniform();
    const Eigen::Vector2d b = sample_uniform_triangle(u1, u2);
    REQUIRE(b.x() >= 0);
    REQUIRE(b.y() >= 0);
    REQUIRE(b.x() + b.y() <= 1 + 1e-12);
    const Eigen::Vector2d u = invert_uniform_triangle(b);
    REQUIRE(u.x() == Approx(u1).margin(1e-9));
    if (u1 > 1e-6) REQUIRE(u.y() == Approx(u2).margin(1e-6));
    obs[std::min(g - 1, int(b.x() * g)) * g + std::min(g - 1, int(b.y() * g))] += 1;
  }
  for (int i = 0; i < g; ++i)
    for (int j = 0; j < g; ++j) {
      // area of the cell [i,i+1]x[j,j+1]/g below the line x + y = 1, relative to the triangle's 1/2
      double a = 0;
      if (i + j + 2 <= g) a = 1.0;
      else if (i + j + 1 == g) a = 0.5;
      exp[i * g + j] = n * a / (g * g) * 2.0;
    }
  test::check_chi_square("uniform triangle", obs, exp, 1e-4);
}

TEST_CASE("Frame is orthonormal and round-trips", "[sampling]") {
  Rng rng = stream(3, StreamDomain::test, 4);
  for (int k = 0; k < 200; ++k) {
    Vec3 n(rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5);
    n.normalize();
    const Frame f(n);
    CHECK(std::abs(f.t.dot(f.b)) < 1e-12);
    CHECK(std::abs(f.t.dot(f.n)) < 1e-12);
    CHECK(f.t.cross(f.b).dot(f.n) == Approx(1.0));
    const Vec3 v(0.3, -0.2, 0.9);
    CHECK((f.to_local(f.to_world(v)) - v).norm() < 1e-12);
  }
}
