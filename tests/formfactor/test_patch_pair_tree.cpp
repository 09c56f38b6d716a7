// The pair enumeration of the analytic route (formfactor/patch_pair_tree.h) and its cut-off
// (formfactor/analytic_form_factors.h, options.cutoff):
//   - on a random scene (small quads and triangles of random orientation above a floor of unit cells) the dual
//     traversal's leaf pairs hold every unordered pair at most once and every pair that a brute-force enumeration
//     finds with G_ij > 0 (cut-off 0) or with F_ij or F_ji above the cut-off (cut-offs 1e-4 and 1e-3); every
//     dropped pair has F_ij, F_ji <= the cut-off, and each row's dropped sum is within its reported bound;
//   - with a cut-off on a closed unoccluded cube: the kept entries equal those without a cut-off bit for bit (near
//     pairs stay exact), each row sums to 1 minus its dropped part with 0 <= 1 - row sum <= cutoff_bound (to float
//     rounding), the dropped pairs are counted and the one-point estimate accounts for the missing row sum
//     within 20 % of it (its documented accuracy at boxes half the distance apart); reciprocity holds;
//   - with a cut-off the patch limit does not apply;
//   - with the completion by cosine rays (cutoff_rays) the closed cube's rows sum to 1 within their standard errors
//     (z-tests, alpha = 1e-3 Sidak), which rejects the uncompleted rows; reciprocity holds.
#include <catch2/catch.hpp>

#include <cmath>
#include <set>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/rng.h"
#include "formfactor/analytic_form_factors.h"
#include "formfactor/patch_pair_tree.h"
#include "formfactor/point_polygon_form_factor.h"
#include "formfactor/polygon_form_factor.h"
#include "patch/patch_builder.h"
#include "support/box_scenes.h"
#include "support/statistics.h"
#include "visibility/embree_visibility.h"

using namespace radwalk;

namespace {

// A floor of 20 x 20 unit cells at z = 0 facing up, and `count` small polygons (side 0.05 to 0.15, random
// orientation; every third a triangle) at random places in [0, 20]^2 x [0.5, 20].
PatchSet random_scene(int count) {
  PatchBuilder b;
  const int m = b.add_material("white", Rgb(0.5, 0.5, 0.5));
  for (int x = 0; x < 20; ++x)
    for (int y = 0; y < 20; ++y) b.add_quad(Vec3(x, y, 0), Vec3(x + 1, y, 0), Vec3(x + 1, y + 1, 0), Vec3(x, y + 1, 0), m);
  Rng rng = stream(11, StreamDomain::test, 0, 0);
  for (int k = 0; k < count; ++k) {
    const Vec3 c(20 * rng.uniform(), 20 * rng.uniform(), 0.5 + 19.5 * rng.uniform());
    Vec3 n(rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5);
    n.normalize();
    const Vec3 u = n.unitOrthogonal(), v = n.cross(u);
    const double s = 0.05 + 0.1 * rng.uniform();
    if (k % 3 == 0)
      b.add_triangle(c, c + s * u, c + s * v, m);
    else
      b.add_quad(c, c + s * u, c + s * (u + v), c + s * v, m);
  }
  return b.build();
}

double row_sum(const SparseF& F, Eigen::Index i) {
  double s = 0;
  for (SparseF::InnerIterator it(F, i); it; ++it) s += it.value();
  return s;
}

}  // namespace

TEST_CASE("pair tree: every pair brute force finds above the cut-off is enumerated, once", "[formfactor][analytic]") {
  const PatchSet ps = random_scene(700);
  const std::size_t N = ps.size();
  // Brute force: G_ij for every unordered pair.
  std::vector<std::vector<double>> G(N, std::vector<double>(N, 0.0));
  for (std::size_t i = 0; i < N; ++i)
    for (std::size_t j = i + 1; j < N; ++j)
      if (patch_may_see(ps, i, j)) G[i][j] = G[j][i] = patch_exchange_area(ps, i, j);
  const PatchPairTree tree(ps);
  for (double tau : {0.0, 1e-4, 1e-3}) {
    INFO("cut-off " << tau);
    const PatchPairEnumeration e = tree.enumerate(tau);
    std::set<std::pair<std::size_t, std::size_t>> kept;
    std::size_t listed = 0;
    for (const auto& lp : e.leaf_pairs) {
      const std::int32_t* A = tree.leaf_begin(lp[0]);
      const std::int32_t* B = tree.leaf_begin(lp[1]);
      for (std::int32_t p = 0; p < tree.leaf_count(lp[0]); ++p)
        for (std::int32_t q = lp[0] == lp[1] ? p + 1 : 0; q < tree.leaf_count(lp[1]); ++q) {
          const std::size_t i = std::size_t(A[p]), j = std::size_t(B[q]);
          kept.insert({std::min(i, j), std::max(i, j)});
          ++listed;
        }
    }
    CHECK(listed == kept.size());  // no pair twice
    std::size_t facing = 0, missed = 0, over_bound = 0, dropped_facing = 0;
    std::vector<double> dropped(N, 0.0);
    for (std::size_t i = 0; i < N; ++i)
      for (std::size_t j = i + 1; j < N; ++j) {
        if (!(G[i][j] > 0)) continue;
        ++facing;
        const double fij = G[i][j] / ps.area[i], fji = G[i][j] / ps.area[j];
        if (kept.count({i, j})) continue;
        ++dropped_facing;
        if (std::max(fij, fji) > tau) ++missed;
        dropped[i] += fij;
        dropped[j] += fji;
      }
    for (std::size_t i = 0; i < N; ++i)
      if (dropped[i] > e.cutoff_bound[i] * (1 + 1e-12)) ++over_bound;
    CHECK(facing > 100000);
    CHECK(missed == 0);
    CHECK(over_bound == 0);
    if (tau == 0) {
      CHECK(dropped_facing == 0);
      CHECK(e.dropped_pairs == 0);
    } else {
      CHECK(dropped_facing > 0);
      CHECK(e.dropped_pairs >= dropped_facing);
      // Fewer pairs computed than brute force would.
      CHECK(kept.size() < N * (N - 1) / 2);
    }
  }
}

TEST_CASE("analytic form factors with a cut-off: closed cube rows sum to 1 minus their reported dropped part",
          "[formfactor][analytic]") {
  const PatchSet ps = test::unit_cube_room(10);
  const std::size_t N = ps.size();
  const EmbreeVisibility vis(ps);
  const AnalyticFormFactors exact = analytic_form_factors(ps, vis);
  AnalyticFormFactorOptions o;
  o.cutoff = 3e-3;
  const AnalyticFormFactors cut = analytic_form_factors(ps, vis, o);
  CHECK(cut.cutoff == 3e-3);
  CHECK(cut.dropped_pairs > 0);
  CHECK(cut.sampled_pairs == 0);
  CHECK(cut.hidden_pairs == 0);
  CHECK(cut.pairs < exact.pairs);
  REQUIRE(cut.cutoff_bound.size() == N);
  REQUIRE(cut.cutoff_estimate.size() == N);
  const SparseF& F = cut.form_factors.F;
  const SparseF& E = exact.form_factors.F;
  std::size_t changed = 0, below = 0, above = 0, estimate_off = 0, rows_cut = 0;
  double worst_reciprocity = 0, worst_estimate = 0, worst_missing = 0, worst_bound_ratio = 0;
  for (std::size_t i = 0; i < N; ++i) {
    for (SparseF::InnerIterator it(F, Eigen::Index(i)); it; ++it) {
      if (it.value() != E.coeff(Eigen::Index(i), it.col())) ++changed;
      const double gij = ps.area[i] * it.value(), gji = ps.area[std::size_t(it.col())] * F.coeff(it.col(), Eigen::Index(i));
      worst_reciprocity = std::max(worst_reciprocity, std::abs(gij - gji) / std::max(gij, gji));
    }
    const double missing = 1 - row_sum(F, Eigen::Index(i));
    if (missing < -1e-6) ++above;
    if (missing > cut.cutoff_bound[i] + 1e-6) ++below;
    if (cut.cutoff_bound[i] > 0) ++rows_cut;
    if (std::abs(missing - cut.cutoff_estimate[i]) > 0.2 * missing + 1e-6) ++estimate_off;
    if (missing > 1e-5) worst_estimate = std::max(worst_estimate, std::abs(cut.cutoff_estimate[i] / missing - 1));
    worst_missing = std::max(worst_missing, missing);
    if (missing > 1e-5) worst_bound_ratio = std::max(worst_bound_ratio, cut.cutoff_bound[i] / missing);
  }
  INFO("worst relative error of the estimate " << worst_estimate << ", largest missing sum " << worst_missing
       << ", largest bound / missing " << worst_bound_ratio << ", pairs " << cut.pairs << " of " << exact.pairs);
  CHECK(rows_cut > N / 2);
  CHECK(changed == 0);
  CHECK(above == 0);
  CHECK(below == 0);
  CHECK(estimate_off == 0);
  CHECK(worst_reciprocity <= 2 * 0x1p-24);
  // The patch limit applies only without a cut-off.
  o.max_patches = N - 1;
  CHECK_NOTHROW(analytic_form_factors(ps, vis, o));
  o.cutoff = 0;
  CHECK_THROWS_AS(analytic_form_factors(ps, vis, o), InputError);
  o.cutoff = -1;
  CHECK_THROWS_AS(analytic_form_factors(ps, vis, o), InputError);
}

TEST_CASE("analytic form factors with a cut-off completed by cosine rays: closed cube rows sum to 1 within their error",
          "[formfactor][analytic]") {
  // The dropped pairs estimated by 4096 cosine rays a row: each row sum is 1 within its standard error (z-tests,
  // family-wise alpha = 1e-3 with Sidak over the rows; the row's standard error sums the entries' variances as if
  // independent, conservative for one row's multinomial counts); the same test rejects the rows left without the
  // completion (their deficit is many standard errors), and F stays reciprocal. The standard error is floored at
  // 1e-6, the float rounding of a stored row sum (rows with nothing dropped have none).
  const PatchSet ps = test::unit_cube_room(10);
  const std::size_t N = ps.size();
  const EmbreeVisibility vis(ps);
  AnalyticFormFactorOptions o;
  o.cutoff = 3e-3;
  o.cutoff_rays = 4096;
  const AnalyticFormFactors a = analytic_form_factors(ps, vis, o);
  o.cutoff_rays = 0;
  const AnalyticFormFactors plain = analytic_form_factors(ps, vis, o);
  CHECK(a.completed_pairs > 0);
  CHECK(a.cutoff_rays == 4096u * N);
  const double z_crit = z_critical(sidak(1e-3, N));
  std::size_t rejected = 0, rejected_plain = 0;
  double worst_reciprocity = 0;
  for (std::size_t i = 0; i < N; ++i) {
    const double se = a.form_factors.row_std_error[i];
    const double z = (row_sum(a.form_factors.F, Eigen::Index(i)) - 1) / std::max(se, 1e-6);
    if (!(std::abs(z) <= z_crit)) ++rejected;
    // The plain rows against the same standard error (where it is not 0): their deficit is the dropped part.
    const double z_plain = (row_sum(plain.form_factors.F, Eigen::Index(i)) - 1) / std::max(se, 1e-6);
    if (!(std::abs(z_plain) <= z_crit)) ++rejected_plain;
    for (SparseF::InnerIterator it(a.form_factors.F, Eigen::Index(i)); it; ++it) {
      const double gij = ps.area[i] * it.value();
      const double gji = ps.area[std::size_t(it.col())] * a.form_factors.F.coeff(it.col(), Eigen::Index(i));
      worst_reciprocity = std::max(worst_reciprocity, std::abs(gij - gji) / std::max(gij, gji));
    }
  }
  INFO("z_crit " << z_crit);
  CHECK(rejected == 0);
  CHECK(rejected_plain > N / 2);
  CHECK(worst_reciprocity <= 2 * 0x1p-24);
  o.cutoff = 0;
  o.cutoff_rays = 16;
  CHECK_THROWS_AS(analytic_form_factors(ps, vis, o), InputError);
}
