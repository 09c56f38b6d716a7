// Alias tables: exact pdf round trip and chi-square goodness of fit (alpha = 1e-3 family-wise, Sidak over the
// two fits), and a check that the fit rejects a wrong distribution.
#include <catch2/catch.hpp>

#include "core/rng.h"
#include "support/stat_checks.h"
#include "walk/alias_table.h"
#include "walk_test_scenes.h"

using namespace radwalk;

namespace {
constexpr double kAlpha = 1e-3;
const double kAlphaEach = sidak(kAlpha, 2);
}  // namespace

TEST_CASE("alias table reproduces its weights (pdf) and passes a chi-square test", "[walk][alias]") {
  const std::vector<double> w = {3, 0, 1, 0.5, 7, 2, 0.01, 4, 0, 1.5, 6, 0.2};
  const AliasTable table(w);
  double total = 0;
  for (double x : w) total += x;
  for (std::size_t i = 0; i < w.size(); ++i) CHECK(table.pdf(i) == Approx(w[i] / total).margin(1e-15));
  const long n = 1'000'000;
  std::vector<double> observed(w.size(), 0), expected(w.size());
  Rng rng = stream(7, StreamDomain::test, 0, 0);
  for (long k = 0; k < n; ++k) observed[table.sample(rng.uniform())] += 1;
  for (std::size_t i = 0; i < w.size(); ++i) expected[i] = n * w[i] / total;
  CHECK(observed[1] == 0);
  CHECK(observed[8] == 0);
  test::check_chi_square("alias table", observed, expected, kAlphaEach);
  // The same counts against a distribution 5% off in one outcome are rejected.
  std::vector<double> wrong = expected;
  wrong[4] *= 1.05;
  wrong[0] -= expected[4] * 0.05;
  CHECK(chi_square_gof_p_value(observed, wrong) < kAlphaEach);
}

TEST_CASE("row alias tables sample F_kj / n_k with the escape outcome", "[walk][alias]") {
  // Open cube (face 5 removed): rows sum to 0.8, escape 0.2. Row 0 scaled to sum above 1: n_0 = s_0.
  SparseF F = test::unit_cube_F({0, 1, 2, 3, 4});
  for (SparseF::InnerIterator it(F, 0); it; ++it) it.valueRef() *= 1.3f;
  const RowAliasTables rows(F);
  for (std::size_t k = 0; k < 5; ++k) {
    double s = 0;
    for (SparseF::InnerIterator it(F, static_cast<Eigen::Index>(k)); it; ++it) s += it.value();
    CHECK(rows.row_sum(k) == Approx(s).epsilon(1e-15));
    CHECK(rows.row_scale(k) == Approx(std::max(s, 1.0)).epsilon(1e-15));
    for (SparseF::InnerIterator it(F, static_cast<Eigen::Index>(k)); it; ++it)
      CHECK(rows.pdf(k, static_cast<PatchIndex>(it.col())) == Approx(it.value() / std::max(s, 1.0)).margin(1e-14));
    CHECK(rows.pdf(k, kEscaped) == Approx(std::max(0.0, 1.0 - s)).margin(1e-14));
  }
  // Chi-square on row 1 (4 patches + escape).
  const long n = 1'000'000;
  std::vector<double> observed(6, 0), expected(6, 0);
  Rng rng = stream(11, StreamDomain::test, 0, 0);
  for (long k = 0; k < n; ++k) {
    const PatchIndex j = rows.sample(1, rng.uniform());
    observed[j < 0 ? 5 : static_cast<std::size_t>(j)] += 1;
  }
  for (PatchIndex j = 0; j < 5; ++j) expected[static_cast<std::size_t>(j)] = n * F.coeff(1, j);
  expected[5] = n * rows.pdf(1, kEscaped);
  CHECK(observed[1] == 0);  // no self-transfer
  std::vector<double> obs, exp;
  for (std::size_t b = 0; b < 6; ++b)
    if (b != 1) {
      obs.push_back(observed[b]);
      exp.push_back(expected[b]);
    }
  test::check_chi_square("row alias table, row 1", obs, exp, kAlphaEach);
}
