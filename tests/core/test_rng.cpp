// Counter-based streams: deterministic per (seed, domain, a, b), distinct across addresses and domains, uniform
// (chi-square).
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "core/rng.h"
#include "support/stat_checks.h"

using namespace radwalk;

namespace {

// Every domain of core/rng.h.
const std::vector<StreamDomain> kDomains = {
    StreamDomain::test,          StreamDomain::form_factor_row, StreamDomain::gather_walk,
    StreamDomain::shoot_particle, StreamDomain::patch_average,  StreamDomain::render_pixel,
    StreamDomain::light_particle, StreamDomain::synthetic_problem, StreamDomain::benchmark,
    StreamDomain::direct_light_shift, StreamDomain::emission_shift, StreamDomain::sobol_particle,
    StreamDomain::measure_walk,   StreamDomain::importance_walk, StreamDomain::visible_direct_light,
    StreamDomain::emitter_form_factor, StreamDomain::jacobi_shift, StreamDomain::analytic_visibility,
    StreamDomain::error_estimate, StreamDomain::discretisation_estimate,
    StreamDomain::hierarchical_direct, StreamDomain::hierarchical_jacobi,
    StreamDomain::hierarchical_variation};

// The first 64 draws of a stream.
std::vector<std::uint32_t> first_draws(Rng rng) {
  std::vector<std::uint32_t> x(64);
  for (auto& v : x) v = rng.next_u32();
  return x;
}

}  // namespace

TEST_CASE("a stream is a pure function of (seed, domain, a, b)", "[rng]") {
  Rng r1 = stream(7, StreamDomain::test, 3, 11), r2 = stream(7, StreamDomain::test, 3, 11);
  Rng r3 = stream(7, StreamDomain::test, 3, 12), r4 = stream(8, StreamDomain::test, 3, 11);
  Rng r5 = stream(7, StreamDomain::gather_walk, 3, 11);
  bool differs3 = false, differs4 = false, differs5 = false;
  for (int k = 0; k < 100; ++k) {
    const auto x = r1.next_u32();
    REQUIRE(x == r2.next_u32());
    differs3 |= x != r3.next_u32();
    differs4 |= x != r4.next_u32();
    differs5 |= x != r5.next_u32();
  }
  CHECK(differs3);
  CHECK(differs4);
  CHECK(differs5);
}

TEST_CASE("different domains never share a stream: first draws differ for every patch and index", "[rng]") {
  // The collision the domains rule out: form-factor row i, gathering walk 0 from patch i, path-traced sample 0
  // of patch i and pixel i would all be (seed, i, 0) without them. For 1000 patches and indices b in {0, 1, 2},
  // every pair of (domain, a, b) addresses with a different domain starts with different draws.
  const std::uint64_t seed = 1;
  std::size_t pairs = 0, equal = 0;
  for (std::uint64_t i = 0; i < 1000; ++i)
    for (std::uint64_t b = 0; b < 3; ++b) {
      std::vector<std::vector<std::uint32_t>> draws;
      for (StreamDomain d : kDomains) draws.push_back(first_draws(stream(seed, d, i, b)));
      for (std::size_t x = 0; x < draws.size(); ++x)
        for (std::size_t y = x + 1; y < draws.size(); ++y) {
          ++pairs;
          // Equal first draws would mean a shared stream; even one equal 32-bit value among 64 is a 2^-26 event.
          std::size_t same = 0;
          for (std::size_t k = 0; k < 64; ++k) same += draws[x][k] == draws[y][k];
          equal += same > 1;
        }
    }
  CHECK(pairs == 1000 * 3 * kDomains.size() * (kDomains.size() - 1) / 2);
  CHECK(equal == 0);
  // The same address in one domain does give the same stream (the check above can see a shared stream).
  CHECK(first_draws(stream(seed, StreamDomain::gather_walk, 5, 0)) ==
        first_draws(stream(seed, StreamDomain::gather_walk, 5, 0)));
}

TEST_CASE("uniform() and uniform_index() pass a chi-square test", "[rng][statistical]") {
  // alpha = 1e-4 family-wise over the two tests below (Sidak), seed fixed.
  const double alpha = sidak(1e-4, 2);
  Rng rng = stream(2024, StreamDomain::test, 1);
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
  Rng rng = stream(2024, StreamDomain::test, 1);
  const int bins = 64, n = 640000;
  std::vector<double> obs(bins, 0), exp(bins, double(n) / bins);
  for (int k = 0; k < n; ++k) obs[static_cast<int>(std::pow(rng.uniform(), 1.05) * bins)] += 1;
  CHECK(chi_square_gof_p_value(obs, exp) < 1e-4);
}

TEST_CASE("RngFamily(seed, domain, a).stream(b) is the stream (seed, domain, a, b)", "[rng]") {
  for (StreamDomain d : kDomains) {
    const RngFamily family(42, d, 7);
    for (std::uint64_t b : {0ull, 1ull, 2ull, 1000000ull, ~0ull}) {
      Rng x = family.stream(b), y = stream(42, d, 7, b);
      for (int k = 0; k < 20; ++k) REQUIRE(x.next_u32() == y.next_u32());
    }
  }
}
