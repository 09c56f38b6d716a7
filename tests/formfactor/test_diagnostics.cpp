// Diagnostics and reciprocity enforcement on hand-made matrices (exact values) and on an estimated cube.
#include <catch2/catch.hpp>

#include <algorithm>

#include "core/error.h"
#include "formfactor/form_factor_diagnostics.h"
#include "formfactor/form_factors.h"
#include "formfactor/reciprocity.h"
#include "formfactor/transpose_slabs.h"
#include "core/rng.h"
#include "support/reciprocity_reference.h"
#include "support/box_scenes.h"
#include "visibility/embree_visibility.h"

using namespace radwalk;

namespace {

SparseF dense_to_sparse(const Eigen::MatrixXf& D) { return D.sparseView(); }

}  // namespace

TEST_CASE("diagnostics of a hand-made matrix", "[formfactor]") {
  // Areas 1, 2, 4. Entries chosen so that row sums, reciprocity errors and standard errors are known.
  Eigen::MatrixXf D(3, 3);
  D << 0.0f, 0.5f, 0.25f,  //
      0.25f, 0.0f, 0.5f,   //
      0.0f, 0.25f, 0.5f;
  const SparseF F = dense_to_sparse(D);
  const std::vector<double> area = {1, 2, 4};
  const std::vector<std::uint32_t> rays = {100, 400, 25}, back = {10, 0, 5};
  const FormFactorDiagnostics d = diagnose_form_factors(F, area, rays, back);
  CHECK(d.row_sum == std::vector<double>{0.75, 0.75, 0.75});
  CHECK(d.back_hit_fraction == std::vector<double>{0.1, 0.0, 0.2});
  // Row 0: pair (0,1): A0 F01 = 0.5, A1 F10 = 0.5 -> 0; pair (0,2): 0.25 vs 0 -> 1.
  CHECK(d.reciprocity_error[0] == 1.0);
  // Row 1: (1,0) 0.5 vs 0.5 -> 0; (1,2): A1 F12 = 1, A2 F21 = 1 -> 0.
  CHECK(d.reciprocity_error[1] == 0.0);
  // Row 2: (2,0): 0 vs 0.25 -> 1.
  CHECK(d.reciprocity_error[2] == 1.0);
  // Standard errors: sqrt(max_j F(1-F) / n).
  CHECK(d.row_std_error[0] == Approx(std::sqrt(0.25 / 100)));
  CHECK(d.row_std_error[1] == Approx(std::sqrt(0.25 / 400)));
  CHECK(d.row_std_error[2] == Approx(std::sqrt(0.25 / 25)));
  // Without ray counts the ray-based fields are empty.
  const FormFactorDiagnostics e = diagnose_form_factors(F, area);
  CHECK(e.row_std_error.empty());
  CHECK(e.back_hit_fraction.empty());
  CHECK_THROWS_AS(diagnose_form_factors(F, {1, 2}), InternalError);
}

TEST_CASE("enforce_reciprocity averages pairs and rescales rows above 1", "[formfactor]") {
  Eigen::MatrixXf D(3, 3);
  D << 0.0f, 0.6f, 0.2f,  //
      0.2f, 0.0f, 0.4f,   //
      0.1f, 0.3f, 0.0f;
  SparseF F = dense_to_sparse(D);
  const std::vector<double> area = {1, 1, 2};
  const SparseF before = F;
  const ReciprocityChange c = enforce_reciprocity(F, area);
  // Means: G01 = (0.6 + 0.2)/2 = 0.4; G02 = (0.2 + 0.2)/2 = 0.2; G12 = (0.4 + 0.6)/2 = 0.5.
  // Row 1 would be 0.4 + 0.5 = 0.9; row 0 is 0.4 + 0.2 = 0.6; row 2 is (0.2 + 0.5)/2 = 0.35.
  CHECK(F.coeff(0, 1) == Approx(0.4f));
  CHECK(F.coeff(1, 0) == Approx(0.4f));
  CHECK(F.coeff(0, 2) == Approx(0.2f));
  CHECK(F.coeff(2, 0) == Approx(0.1f));
  CHECK(F.coeff(1, 2) == Approx(0.5f));
  CHECK(F.coeff(2, 1) == Approx(0.25f));
  CHECK(c.rows_rescaled == 0);
  // Relative changes: (0,1): 0.2/0.6; (1,0): 0.2/0.4; (1,2): 0.1/0.5; (2,1): 0.05/0.3; others 0.
  CHECK(c.max_relative_change == Approx(0.5));
  CHECK(c.mean_relative_change == Approx((0.2 / 0.6 + 0.5 + 0.2 + 0.05 / 0.3) / 6));
  CHECK(F.nonZeros() == before.nonZeros());

  // A row pushed above 1 is rescaled to 1; an entry hit from one side appears on both.
  Eigen::MatrixXf H(2, 2);
  H << 0.0f, 0.9f,  //
      1.0f, 0.0f;
  SparseF G = dense_to_sparse(H);
  const ReciprocityChange r = enforce_reciprocity(G, {2, 1});
  // A0 F01 = 1.8, A1 F10 = 1 -> 1.4: F01 = 0.7, F10 = 1.4 -> rescaled to 1.
  CHECK(G.coeff(0, 1) == Approx(0.7f));
  CHECK(G.coeff(1, 0) == 1.0f);
  CHECK(r.rows_rescaled == 1);
  CHECK(r.max_row_excess == Approx(0.4));
  Eigen::MatrixXf O(2, 2);
  O << 0.0f, 0.5f, 0.0f, 0.0f;
  SparseF one_sided = dense_to_sparse(O);
  enforce_reciprocity(one_sided, {1, 1});
  CHECK(one_sided.coeff(0, 1) == Approx(0.25f));
  CHECK(one_sided.coeff(1, 0) == Approx(0.25f));
  CHECK_THROWS_AS(enforce_reciprocity(one_sided, {1, 0}), InputError);
  CHECK_THROWS_AS(enforce_reciprocity(one_sided, {1}), InternalError);
}

TEST_CASE("diagnostics of an estimated closed cube", "[formfactor]") {
  const PatchSet ps = test::unit_cube_room(2);
  const EmbreeVisibility vis(ps);
  FormFactorOptions opt;
  opt.rays_per_patch = 20000;
  FormFactors ff = estimate_form_factors(ps, vis, opt);
  const FormFactorDiagnostics d = diagnose_form_factors(ff.F, ps.area, ff.rays, ff.back_hits);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    INFO("row " << i << " sum " << d.row_sum[i] << " back " << d.back_hit_fraction[i] << " reciprocity "
                << d.reciprocity_error[i] << " se " << d.row_std_error[i]);
    CHECK(std::abs(d.row_sum[i] - 1) <= 24 * 0x1p-24);
    CHECK(d.back_hit_fraction[i] == 0);
    CHECK(d.row_std_error[i] > 0);
    CHECK(d.row_std_error[i] < 0.004);  // sqrt(0.25 / 20000)
    CHECK(d.reciprocity_error[i] < 1);  // every pair seen from both sides
  }
  const ReciprocityChange c = enforce_reciprocity(ff.F, ps.area);
  const FormFactorDiagnostics after = diagnose_form_factors(ff.F, ps.area);
  double worst = 0;
  for (double e : after.reciprocity_error) worst = std::max(worst, e);
  // Averaging pushes some rows of a closed scene above 1; rescaling them leaves a reciprocity error of at most
  // their relative excess (plus float rounding), and the excess is of the order of the row sums' noise.
  const double bound = c.max_row_excess / (1 + c.max_row_excess) + 1e-6;
  INFO("max relative change " << c.max_relative_change << ", rows rescaled " << c.rows_rescaled << ", max excess "
                              << c.max_row_excess << ", reciprocity error after " << worst << " (bound " << bound
                              << ")");
  CHECK(worst <= bound);
  CHECK(c.max_row_excess < 0.05);
  CHECK(c.max_relative_change > 0);
  // Rows that were not rescaled and whose partners were not either are exactly reciprocal (float rounding).
  std::vector<bool> rescaled(ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i) rescaled[i] = after.row_sum[i] > 1 - 1e-6;  // rescaled rows sum to 1
  for (std::size_t i = 0; i < ps.size(); ++i)
    for (SparseF::InnerIterator it(ff.F, Eigen::Index(i)); it; ++it) {
      if (rescaled[i] || rescaled[it.index()]) continue;
      const double gij = ps.area[i] * it.value(), gji = ps.area[it.index()] * ff.F.coeff(it.index(), Eigen::Index(i));
      CHECK(std::abs(gij - gji) <= 1e-6 * std::max(gij, gji));
    }
  for (double s : after.row_sum) CHECK(s <= 1 + 1e-6);
}

namespace {

// A random N x N form-factor-like matrix: each pair i <= j drawn with probability `density`, then stored on both
// sides with probability 9/10, else on one side only (which one at random); a stored entry is an explicit zero
// with probability 1/8, otherwise uniform in (0, 1) / (N density). Columns increase within each row
// (setFromTriplets).
SparseF random_matrix(int N, double density, std::uint64_t seed) {
  Rng rng = stream(seed, StreamDomain::test, std::uint64_t(N), 0);
  std::vector<Eigen::Triplet<float, std::int32_t>> t;
  const auto value = [&] { return rng.uniform_index(8) == 0 ? 0.0f : float(rng.uniform() / (N * density)); };
  for (int i = 0; i < N; ++i)
    for (int j = i; j < N; ++j) {
      if (rng.uniform() >= density) continue;
      const double side = rng.uniform();
      if (side < 0.9 || i == j) {
        t.emplace_back(i, j, value());
        if (i != j) t.emplace_back(j, i, value());
      } else if (side < 0.95) {
        t.emplace_back(i, j, value());
      } else {
        t.emplace_back(j, i, value());
      }
    }
  SparseF F(N, N);
  F.setFromTriplets(t.begin(), t.end());
  F.makeCompressed();
  return F;
}

std::vector<double> random_areas(int N, std::uint64_t seed) {
  Rng rng = stream(seed, StreamDomain::test, std::uint64_t(N), 1);
  std::vector<double> a(static_cast<std::size_t>(N));
  for (double& x : a) x = 0.25 + 4 * rng.uniform();
  return a;
}

}  // namespace

TEST_CASE("transposed slabs give every column's rows in increasing order, whatever the slab size", "[formfactor]") {
  const SparseF F = random_matrix(57, 0.2, 5);
  const SparseF T = SparseF(F.transpose());
  for (const std::size_t max_entries : {std::size_t(1), std::size_t(7), std::size_t(40), std::size_t(1) << 20}) {
    INFO("max_entries " << max_entries);
    TransposeSlabs slabs(F, max_entries);
    std::size_t next_column = 0, slabs_seen = 0;
    while (slabs.next()) {
      ++slabs_seen;
      CHECK(slabs.begin() == next_column);
      for (std::size_t c = slabs.begin(); c < slabs.end(); ++c) {
        const TransposedRow r = slabs.row(c);
        std::vector<std::int32_t> rows, want;
        std::vector<float> values, want_values;
        for (std::size_t k = 0; k < r.size; ++k) {
          rows.push_back(r.entries[k].row);
          values.push_back(r.entries[k].value);
        }
        for (SparseF::InnerIterator it(T, Eigen::Index(c)); it; ++it) {
          want.push_back(std::int32_t(it.index()));
          want_values.push_back(it.value());
        }
        CHECK(rows == want);
        CHECK(values == want_values);
      }
      next_column = slabs.end();
    }
    CHECK(next_column == 57);
    CHECK(slabs_seen == slabs.slab_count());
    if (max_entries == 1) CHECK(slabs_seen == 57);  // one column per slab when none fits beside another
  }
}

TEST_CASE("reciprocity diagnostics and enforcement equal the brute-force and binary-search references bit for bit",
          "[formfactor]") {
  long one_sided_rows = 0, two_sided_rows = 0;
  for (const double density : {0.05, 0.3, 0.9}) {
    const int N = 83;
    const SparseF F = random_matrix(N, density, 17);
    const std::vector<double> area = random_areas(N, 17);
    INFO("density " << density << ", " << F.nonZeros() << " non-zeros");
    const FormFactorDiagnostics d = diagnose_form_factors(F, area);
    CHECK(d.reciprocity_error == test::brute_force_reciprocity_error(F, area));
    CHECK(d.reciprocity_error == test::binary_search_reciprocity_error(F, area));
    // Both cases are covered: rows with a one-sided pair (error 1) and rows with two-sided pairs only (error < 1).
    one_sided_rows += std::count(d.reciprocity_error.begin(), d.reciprocity_error.end(), 1.0);
    two_sided_rows += std::count_if(d.reciprocity_error.begin(), d.reciprocity_error.end(),
                                    [](double e) { return e > 0 && e < 1; });

    SparseF now = F, former = F;
    const ReciprocityChange c = enforce_reciprocity(now, area);
    const ReciprocityChange r = test::binary_search_enforce_reciprocity(former, area);
    CHECK(c.max_relative_change == r.max_relative_change);
    CHECK(c.mean_relative_change == r.mean_relative_change);
    CHECK(c.rows_rescaled == r.rows_rescaled);
    CHECK(c.max_row_excess == r.max_row_excess);
    REQUIRE(now.nonZeros() == former.nonZeros());
    CHECK(std::equal(now.outerIndexPtr(), now.outerIndexPtr() + N + 1, former.outerIndexPtr()));
    CHECK(std::equal(now.innerIndexPtr(), now.innerIndexPtr() + now.nonZeros(), former.innerIndexPtr()));
    CHECK(std::equal(now.valuePtr(), now.valuePtr() + now.nonZeros(), former.valuePtr()));
  }
  CHECK(one_sided_rows > 0);
  CHECK(two_sided_rows > 0);
}
