// Counter-based streams: deterministic per (seed, a, b), distinct across triples, uniform (chi-square).
#include <catch2/catch.hpp>
#include <vector>

#include "core/rng.h"
#include "support/stat_checks.h"

using namespace radwalk;

TEST_CASE("a stream is a pure function of (seed, a, b)", "[rng]") {
  Rng r1(7, 3, 11), r2(7, 3, 11), r3(7, 3, 12), r4(8, 3, 11);
  bool differs3 = false, differs4 = false;
  for (int k = 0; k < 100; ++k) {
    const auto x = r1.next_u32();
    REQUIRE(x == r2.next_u32());
    differs3 |= x != r3.next_u32();
    differs4 |= x != r4.next_u32();
  }
  CHECK(differs3);
  CHECK(differs4);
}

TEST_CASE("uniform() and uniform_index() pass a chi-square test", "[rng][statistical]") {
  // alpha = 1e-4 family-wise over the two tests below (Sidak), seed fixed.
  const double alpha = sidak(1e-4, 2);
  Rng rng(2024, 1);
  const int bins = 64, n = 640000;
  std::vector<double> obs(bins, 0), exp(bins, double(n) / bins);
  for (int k = 0; k < n; ++k) {
    const double u = rng.uniform();
    REQUIRE(u >= 0.0);
    REQUIRE(u < 1.0);
    obs[static_cast<int>(u * bins)] += 1;
  }
  test::check_chi_square("uniform", obs, exp, alpha);

  std::vector<double> obs2(37, 0), exp2(37, double(n) / 37);
  for (int k = 0; k < n; ++k) obs2[rng.uniform_index(37)] += 1;
  test::check_chi_square("uniform_index(37)", obs2, exp2, alpha);
}

TEST_CASE("a biased generator fails the same chi-square test", "[rng][statistical]") {
  // The test above must be able to fail: u^1.05 is slightly non-uniform and is rejected.
  Rng rng(2024, 1);
  const int bins = 64, n = 640000;
  std::vector<double> obs(bins, 0), exp(bins, double(n) / bins);
  for (int k = 0; k < n; ++k) obs[static_cast<int>(std::pow(rng.uniform(), 1.05) * bins)] += 1;
  CHECK(chi_square_gof_p_value(obs, exp) < 1e-4);
}

TEST_CASE("RngFamily(seed, a).stream(b) is the stream Rng(seed, a, b)", "[rng]") {
  const RngFamily family(42, 7);
  for (std::uint64_t b : {0ull, 1ull, 2ull, 1000000ull, ~0ull}) {
    Rng x = family.stream(b), y(42, 7, b);
    for (int k = 0; k < 20; ++k) REQUIRE(x.next_u32() == y.next_u32());
  }
}
