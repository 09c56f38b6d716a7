// Diagnostics and reciprocity enforcement on hand-made matrices (exact values) and on an estimated cube.
#include <catch2/catch.hpp>

#include "core/error.h"
#include "formfactor/form_factor_diagnostics.h"
#include "formfactor/form_factors.h"
#include "formfactor/reciprocity.h"
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
