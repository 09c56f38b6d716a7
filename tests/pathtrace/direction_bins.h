#pragma once
// Direction samplers against their pdfs, for the path tracer's chi-square tests (test-only): uniform directions
// on the sphere, and the observed and expected counts of a sampler in bins of (cos theta, phi) over the upper
// hemisphere, to be judged with check_chi_square (support/stat_checks.h).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <vector>

#include "core/rng.h"
#include "core/types.h"

namespace radwalk::test {

// Uniform direction on the sphere (pdf 1 / (4 pi)).
inline Vec3 uniform_sphere(double u1, double u2) {
  const double z = 1 - 2 * u1, r = std::sqrt(std::max(0.0, 1 - z * z)), phi = 2 * kPi * u2;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

struct BinCounts {
  std::vector<double> observed, expected;
};

// n samples of a direction sampler against its solid-angle pdf over the upper hemisphere, in nc x nphi bins of
// (cos theta, phi), plus one bin for "no sample". Expected counts by midpoint integration of the pdf (sub x sub
// points per bin; dw = dcos dphi).
inline BinCounts direction_counts(const std::function<bool(Rng&, Vec3&)>& sample,
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
  return {obs, exp};
}

}  // namespace radwalk::test
