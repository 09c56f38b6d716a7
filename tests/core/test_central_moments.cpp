// The fourth-moment accumulator behind the variance of the variance (core/moments.h CentralMoments4): blocks merged
// in any split give the two-pass moments of all samples, and VOV = sum d^4 / (sum d^2)^2 - 1/n takes its exact value
// on samples whose moments are known in closed form.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "core/moments.h"
#include "core/rng.h"

using namespace radwalk;

namespace {

// Two passes over all samples: the definition, sum (x - mean)^k.
CentralMoments4 direct(const std::vector<Rgb>& x) {
  CentralMoments4 m;
  m.n = static_cast<long>(x.size());
  for (const Rgb& v : x) m.mean += v;
  m.mean /= static_cast<double>(x.size());
  for (const Rgb& v : x) {
    const Rgb d = v - m.mean;
    m.M2 += d * d;
    m.M3 += d * d * d;
    m.M4 += d * d * d * d;
  }
  return m;
}

void check_close(const Rgb& a, const Rgb& b, double scale) {
  for (int c = 0; c < 3; ++c) CHECK(std::abs(a[c] - b[c]) <= 1e-11 * scale);
}

}  // namespace

TEST_CASE("central moments merged from blocks equal the two passes over all samples", "[moments]") {
  // Heavy-tailed samples (exp of a Gaussian-like sum, spread over 8 decades) and a mean far from 0.
  Rng rng(RngFamily(7, StreamDomain::test, 0).stream(0));
  std::vector<Rgb> x(3001);
  for (Rgb& v : x)
    for (int c = 0; c < 3; ++c) v[c] = 5.0 + std::exp(6.0 * (rng.uniform() + rng.uniform() + rng.uniform() - 1.5));
  const CentralMoments4 all = direct(x);
  const std::size_t block = GENERATE(as<std::size_t>{}, 1, 7, 256, 1000, 3001);
  CentralMoments4 merged;
  for (std::size_t b = 0; b < x.size(); b += block)
    merged.merge(CentralMoments4::of(x.data() + b, std::min(block, x.size() - b)));
  CHECK(merged.n == all.n);
  check_close(merged.mean, all.mean, all.mean.abs().maxCoeff());
  check_close(merged.M2, all.M2, all.M2.abs().maxCoeff());
  check_close(merged.M3, all.M3, all.M3.abs().maxCoeff());
  check_close(merged.M4, all.M4, all.M4.abs().maxCoeff());
  check_close(merged.vov(), all.M4 / (all.M2 * all.M2) - 1.0 / 3001.0, 1.0);
}

TEST_CASE("the variance of the variance on samples with known moments", "[moments]") {
  const long n = 1024;
  SECTION("equal samples: VOV 0 (nothing to distrust)") {
    const std::vector<Rgb> x(n, Rgb::Constant(0.3));
    CHECK((CentralMoments4::of(x.data(), x.size()).vov() == 0).all());
  }
  SECTION("half zeros, half ones: d = +-1/2, so sum d^4 / (sum d^2)^2 = 1/n and VOV = 0") {
    std::vector<Rgb> x(n);
    for (long i = 0; i < n; ++i) x[i] = Rgb::Constant(double(i % 2));
    CHECK((CentralMoments4::of(x.data(), x.size()).vov().abs() < 1e-15).all());
  }
  SECTION("one bright sample among n zeros: VOV = ((n-1)^3 + 1) / (n^2 (n-1)) - 1/n, about 1 (unreliable)") {
    std::vector<Rgb> x(n, Rgb::Zero());
    x[517] = Rgb(1, 1e6, 1e-6);  // scale-free
    const double nn = double(n);
    const double expected = ((nn - 1) * (nn - 1) * (nn - 1) + 1) / (nn * nn * (nn - 1)) - 1 / nn;
    const Rgb v = CentralMoments4::of(x.data(), x.size()).vov();
    for (int c = 0; c < 3; ++c) CHECK(v[c] == Approx(expected).epsilon(1e-12));
    CHECK((v > kVovReliable).all());
  }
}
