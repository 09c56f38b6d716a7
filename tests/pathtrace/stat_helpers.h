#pragma once
// Hypothesis-test helpers shared by the path tracer's tests (test-only).
#include <catch2/catch.hpp>
#include <cmath>
#include <cstddef>
#include <functional>
#include <vector>

#include "core/rng.h"
#include "core/solution.h"
#include "core/stats.h"
#include "core/types.h"

namespace radwalk::test {

// Running mean and unbiased variance.
struct Moments {
  double n = 0, sum = 0, sum2 = 0;
  void add(double x) {
    n += 1;
    sum += x;
    sum2 += x * x;
  }
  double mean() const { return sum / n; }
  double var() const { return std::max(0.0, (sum2 - sum * sum / n) / (n - 1)); }
  double se() const { return std::sqrt(var() / n); }
};

// z-test of an estimate against an exact value; prints operands on failure.
inline void check_z(const char* what, double estimate, double se, double exact, double z_crit) {
  INFO(what << ": estimate " << estimate << " +- " << se << " (se), exact " << exact << ", |z| limit " << z_crit);
  REQUIRE(se > 0);
  CHECK(std::abs(estimate - exact) / se < z_crit);
}

// Two-sample z-tests: every patch and channel of two independent estimates agree, |B_a - B_b| / sqrt(se_a^2 +
// se_b^2) < z_crit (equal, where both standard errors are 0); prints both operands on failure.
inline void check_solutions_agree(const Solution& a, const Solution& b, double z_crit) {
  for (Eigen::Index i = 0; i < a.B.rows(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double se = std::hypot(a.B_se(i, c), b.B_se(i, c));
      INFO(a.method << " vs " << b.method << ", patch " << i << " channel " << c << ": " << a.B(i, c) << " +- "
                    << a.B_se(i, c) << " vs " << b.B(i, c) << " +- " << b.B_se(i, c));
      // Both without variance (e.g. a patch no sample could light): then they must agree exactly.
      if (se == 0)
        CHECK(a.B(i, c) == b.B(i, c));
      else
        CHECK(std::abs(a.B(i, c) - b.B(i, c)) / se < z_crit);
    }
}

// Uniform direction on the sphere (pdf 1 / (4 pi)).
inline Vec3 uniform_sphere(double u1, double u2) {
  const double z = 1 - 2 * u1, r = std::sqrt(std::max(0.0, 1 - z * z)), phi = 2 * kPi * u2;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// Chi-square test of a direction sampler against its solid-angle pdf over the upper hemisphere, in nc x nphi
// bins of (cos theta, phi), plus one bin for "no sample". Expected counts by midpoint integration of the pdf
// (sub x sub points per bin; dw = dcos dphi). Returns the p-value.
inline double direction_chi_square(const std::function<bool(Rng&, Vec3&)>& sample,
                                   const std::function<double(const Vec3&)>& pdf, int n, std::uint64_t seed,
                                   int nc = 20, int nphi = 20, int sub = 24) {
  std::vector<double> obs(nc * nphi + 1, 0.0), exp(nc * nphi + 1, 0.0);
  Rng rng = stream(seed, StreamDomain::test, 0);
  for (int k = 0; k < n; ++k) {
    Vec3 w;
    if (!sample(rng, w) || w.z() <= 0) {
      obs.back() += 1;
      continue;
    }
    const int ic = std::min(nc - 1, static_cast<int>(w.z() * nc));
    double phi = std::atan2(w.y(), w.x());
    if (phi < 0) phi += 2 * kPi;
    const int ip = std::min(nphi - 1, static_cast<int>(phi / (2 * kPi) * nphi));
    obs[ic * nphi + ip] += 1;
  }
  double total = 0;
  for (int ic = 0; ic < nc; ++ic)
    for (int ip = 0; ip < nphi; ++ip) {
      double integral = 0;
      const double dc = 1.0 / nc / sub, dp = 2 * kPi / nphi / sub;
      for (int a = 0; a < sub; ++a)
        for (int b = 0; b < sub; ++b) {
          const double c = (ic + (a + 0.5) / sub) / nc;
          const double phi = (ip + (b + 0.5) / sub) * 2 * kPi / nphi;
          const double s = std::sqrt(std::max(0.0, 1 - c * c));
          integral += pdf(Vec3(s * std::cos(phi), s * std::sin(phi), c)) * dc * dp;
        }
      exp[ic * nphi + ip] = n * integral;
      total += integral;
    }
  exp.back() = n * std::max(0.0, 1.0 - total);
  return chi_square_gof_p_value(obs, exp);
}

}  // namespace radwalk::test
