// The least-squares closure and reciprocity adjustment (formfactor/closure.h, docs/theory/closure.md) on small
// matrices: rows sum to 1 and A_i F_ij = A_j F_ji to float rounding, the pattern is kept, entries stay
// non-negative (clipped where the correction would make them negative), an exact F is left unchanged, and the
// refusals.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "formfactor/closure.h"

using namespace radwalk;

namespace {

// The unit cube's exact F (face i opposite face i ^ 1), values as tests/support/reference_problems.h.
constexpr double kOpposite = 0.199824896, kAdjacent = 0.200043776;

SparseF from_dense(const std::vector<std::vector<double>>& d) {
  std::vector<Eigen::Triplet<float, std::int32_t>> t;
  for (std::size_t i = 0; i < d.size(); ++i)
    for (std::size_t j = 0; j < d.size(); ++j)
      if (d[i][j] != 0) t.emplace_back(std::int32_t(i), std::int32_t(j), float(d[i][j]));
  SparseF F(Eigen::Index(d.size()), Eigen::Index(d.size()));
  F.setFromTriplets(t.begin(), t.end());
  return F;
}

std::vector<std::vector<double>> cube(double noise) {
  std::vector<std::vector<double>> d(6, std::vector<double>(6, 0.0));
  unsigned state = 12345;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) {
      if (i == j) continue;
      state = state * 1103515245u + 12345u;
      const double u = double((state >> 8) & 0xffff) / 65535.0 - 0.5;  // deterministic in [-0.5, 0.5]
      d[std::size_t(i)][std::size_t(j)] = ((i ^ 1) == j ? kOpposite : kAdjacent) * (1 + noise * u);
    }
  return d;
}

double value(const SparseF& F, int i, int j) { return double(F.coeff(i, j)); }

}  // namespace

TEST_CASE("closure: a perturbed cube F is closed and reciprocal to float rounding, pattern kept, non-negative",
          "[closure]") {
  const std::vector<double> area = {1, 1, 2, 2, 0.5, 0.5};  // unequal areas (the F is then not a real cube's)
  SparseF F = from_dense(cube(0.2));
  const Eigen::Index nnz = F.nonZeros();
  const SparseF before = F;
  const std::vector<std::uint32_t> rays = {1000, 2000, 500, 1000, 4000, 1000};
  const ClosureChange c = enforce_closure(F, area, rays);
  CHECK(F.nonZeros() == nnz);
  CHECK(c.clipped == 0);
  for (int i = 0; i < 6; ++i) {
    double row = 0, max_change = 0;
    for (int j = 0; j < 6; ++j) {
      row += value(F, i, j);
      CHECK(value(F, i, j) >= 0);
      max_change = std::max(max_change, std::abs(value(F, i, j) - value(before, i, j)));
      const double x = area[std::size_t(i)] * value(F, i, j), y = area[std::size_t(j)] * value(F, j, i);
      CHECK(std::abs(x - y) <= 4e-7 * std::max(x, y));  // float rounding of F' = X'/A
    }
    INFO("row " << i << " sums to " << row);
    CHECK(std::abs(row - 1) <= 1e-6);
    CHECK(c.row_max_change[std::size_t(i)] == Approx(max_change).margin(1e-7));
  }
  CHECK(c.max_row_defect_after <= 1e-6);
  CHECK(c.max_reciprocity_defect_after <= 4e-7);
  CHECK(c.max_row_defect_before > 0.01);  // the test moved something
}

TEST_CASE("closure: the exact cube F is left as it is (to float rounding)", "[closure]") {
  SparseF F = from_dense(cube(0.0));
  const SparseF before = F;
  const ClosureChange c = enforce_closure(F, std::vector<double>(6, 1.0), {});
  CHECK(c.max_change <= 1e-6);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) CHECK(std::abs(value(F, i, j) - value(before, i, j)) <= 1e-6);
}

TEST_CASE("closure: entries that the correction would make negative are clipped to 0 and the rest still closes",
          "[closure]") {
  // Very noisy 8-patch matrices (every entry times a factor in [0.02, 1.98], sparse in a random pattern, unequal
  // areas and ray counts) until one needs the active set; there the result must still be closed, reciprocal and
  // non-negative.
  unsigned state = 7;
  const auto uniform = [&state] {
    state = state * 1103515245u + 12345u;
    return double((state >> 8) & 0xffff) / 65536.0;
  };
  bool clipped_once = false;
  for (int trial = 0; trial < 500 && !clipped_once; ++trial) {
    const int n = 8;
    std::vector<double> area(n);
    std::vector<std::uint32_t> rays(n);
    for (int i = 0; i < n; ++i) area[std::size_t(i)] = 0.5 + uniform(), rays[std::size_t(i)] = 10 + unsigned(100 * uniform());
    std::vector<std::vector<double>> d(n, std::vector<double>(n, 0.0));
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        if (i != j && uniform() < 0.7) d[std::size_t(i)][std::size_t(j)] = (0.02 + 1.96 * uniform()) / (0.7 * (n - 1));
    SparseF F = from_dense(d);
    ClosureChange c;
    try {
      c = enforce_closure(F, area, rays);
    } catch (const InputError&) {
      continue;  // too noisy for any closed adjustment: refused, which is allowed
    }
    if (c.clipped == 0) continue;
    clipped_once = true;
    INFO("trial " << trial << ": " << c.clipped << " clipped in " << c.rounds << " rounds");
    for (int i = 0; i < n; ++i) {
      double row = 0;
      for (int j = 0; j < n; ++j) {
        CHECK(value(F, i, j) >= 0);
        row += value(F, i, j);
      }
      CHECK(std::abs(row - 1) <= 1e-5);
    }
    CHECK(c.max_reciprocity_defect_after <= 1e-6);
  }
  CHECK(clipped_once);
}

TEST_CASE("closure: a patch that sees nothing, or a bad area, is refused naming the patch", "[closure]") {
  std::vector<std::vector<double>> d = {{0, 1, 0}, {1, 0, 0}, {0, 0, 0}};
  SparseF F = from_dense(d);
  try {
    enforce_closure(F, {1, 1, 1}, {});
    FAIL("no refusal");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("patch 2") != std::string::npos);
  }
  SparseF G = from_dense(cube(0.1));
  CHECK_THROWS_AS(enforce_closure(G, {1, 1, 1, 0, 1, 1}, {}), InputError);
}
