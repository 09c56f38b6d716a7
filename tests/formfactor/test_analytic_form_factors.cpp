// The analytic form-factor route (formfactor/analytic_form_factors.h):
//   - an unoccluded closed cube (k x k patches a face, quads and with triangles): every pair proven clear, rows
//     sum to 1 to 1e-6, the face-to-face sums equal Howell C-11 and C-14 to 1e-6 (F is stored in float), and
//     A_i F_ij = A_j F_ji to float rounding;
//   - a box standing on the floor of a closed cube: the floor patches under it get rows of exactly 0, straddling
//     patches their visible fraction; every entry estimated by rays is unbiased against an independent Monte Carlo
//     estimate of the same entry (estimate_form_factors, 2^15 rays a patch): two-sample z-tests, family-wise
//     alpha = 1e-3 (Sidak); every row sum is 1 within its standard error except the rows under the box (z-tests,
//     alpha = 1e-3); no row above 1 + 1e-6;
//   - bit-identical F on 1 and 2 threads; refusal above max_patches.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "formfactor/analytic_form_factors.h"
#include "formfactor/form_factors.h"
#include "formfactor/patch_shaft.h"
#include "patch/patch_builder.h"
#include "support/box_scenes.h"
#include "support/stat_checks.h"
#include "support/statistics.h"
#include "support/view_factors.h"
#include "visibility/embree_visibility.h"

using namespace radwalk;

namespace {

double row_sum(const SparseF& F, Eigen::Index i) {
  double s = 0;
  for (SparseF::InnerIterator it(F, i); it; ++it) s += it.value();
  return s;
}

double entry(const SparseF& F, Eigen::Index i, Eigen::Index j) { return F.coeff(i, j); }

// The closed cube [0,1]^3 with k x k patches a face and a box [0.3, 0.7]^2 x [0, 0.3] standing on its floor
// (outward faces, m x m a face, its bottom lying on the floor facing down).
PatchSet cube_with_box(int k, int m) {
  PatchBuilder b;
  const int white = b.add_material("white", Rgb(0.5, 0.5, 0.5));
  test::add_box(b, Vec3(0, 0, 0), Vec3(1, 1, 1), k, true, white);
  test::add_box(b, Vec3(0.3, 0.3, 0), Vec3(0.7, 0.7, 0.3), m, false, white);
  return b.build();
}

}  // namespace

TEST_CASE("analytic form factors: unoccluded cube, rows sum to 1 and faces match C-11 and C-14",
          "[formfactor][analytic]") {
  for (bool triangles : {false, true}) {
    const int k = 4;
    const PatchSet ps = test::unit_cube_room(k, triangles);
    const EmbreeVisibility vis(ps);
    const AnalyticFormFactors a = analytic_form_factors(ps, vis);
    INFO("triangles " << triangles);
    CHECK(a.sampled_pairs == 0);
    CHECK(a.hidden_pairs == 0);
    CHECK(a.visibility_rays == 0);
    CHECK(a.rows_scaled == 0);
    const SparseF& F = a.form_factors.F;
    const std::size_t N = ps.size();
    double worst_row = 0, worst_reciprocity = 0;
    for (std::size_t i = 0; i < N; ++i) {
      worst_row = std::max(worst_row, std::abs(row_sum(F, Eigen::Index(i)) - 1));
      CHECK(a.form_factors.row_std_error[i] == 0);
      for (SparseF::InnerIterator it(F, Eigen::Index(i)); it; ++it) {
        const double gij = ps.area[i] * it.value(), gji = ps.area[std::size_t(it.col())] * entry(F, it.col(), Eigen::Index(i));
        worst_reciprocity = std::max(worst_reciprocity, std::abs(gij - gji) / std::max(gij, gji));
      }
    }
    CHECK(worst_row <= 1e-6);
    CHECK(worst_reciprocity <= 2 * 0x1p-24);
    // Face sums: patches are in face order (x=0, x=1, y=0, y=1, z=0, z=1), N / 6 each; A_face F_face,face' =
    // sum of A_i F_ij over the two faces' patches.
    const std::size_t per = N / 6;
    const auto face_factor = [&](std::size_t f, std::size_t g) {
      double s = 0;
      for (std::size_t i = f * per; i < (f + 1) * per; ++i)
        for (std::size_t j = g * per; j < (g + 1) * per; ++j) s += ps.area[i] * entry(F, Eigen::Index(i), Eigen::Index(j));
      return s;  // the face's area is 1
    };
    CHECK(face_factor(0, 1) == Approx(test::parallel_rectangles(1, 1, 1)).epsilon(1e-6));
    CHECK(face_factor(4, 5) == Approx(test::parallel_rectangles(1, 1, 1)).epsilon(1e-6));
    CHECK(face_factor(0, 2) == Approx(test::perpendicular_rectangles(1, 1, 1)).epsilon(1e-6));
    CHECK(face_factor(3, 5) == Approx(test::perpendicular_rectangles(1, 1, 1)).epsilon(1e-6));
  }
}

TEST_CASE("analytic form factors: a box on the floor, hidden rows 0, estimates unbiased against Monte Carlo",
          "[formfactor][analytic]") {
  const int k = 6, m = 2;
  const PatchSet ps = cube_with_box(k, m);
  const EmbreeVisibility vis(ps);
  const AnalyticFormFactors a = analytic_form_factors(ps, vis);
  const SparseF& F = a.form_factors.F;
  REQUIRE(a.sampled_pairs > 0);
  CHECK(a.clear_pairs > 0);
  // The floor (z = 0) is face 4 of the room: patches 4 k^2 .. 5 k^2 - 1, cell (a, c) covering x in [a/k, (a+1)/k],
  // y in [c/k, (c+1)/k] (add_box's order: u = x, v = y for f = z).
  const std::size_t floor0 = 4 * std::size_t(k * k);
  int under = 0, straddling = 0;
  std::vector<double> free_fraction(ps.size(), -1.0);
  for (int ax = 0; ax < k; ++ax)
    for (int cy = 0; cy < k; ++cy) {
      const std::size_t i = floor0 + std::size_t(ax * k + cy);
      const double x0 = double(ax) / k, x1 = double(ax + 1) / k, y0 = double(cy) / k, y1 = double(cy + 1) / k;
      const bool inside = x0 >= 0.3 && x1 <= 0.7 && y0 >= 0.3 && y1 <= 0.7;
      const bool overlaps = x1 > 0.3 && x0 < 0.7 && y1 > 0.3 && y0 < 0.7;
      REQUIRE(std::abs(ps.centroid[i].z()) < 1e-12);
      if (inside) {
        ++under;
        CHECK(row_sum(F, Eigen::Index(i)) == 0.0);
      } else if (overlaps) {
        ++straddling;
        const double xs = std::min(x1, 0.7) - std::max(x0, 0.3), ys = std::min(y1, 0.7) - std::max(y0, 0.3);
        free_fraction[i] = 1 - xs * ys * k * k;  // the fraction of the cell not under the box: its exact row sum
      }
    }
  CHECK(under == 4);
  CHECK(straddling == 12);

  // Monte Carlo reference, and z-tests: entries that were sampled, and row sums.
  FormFactorOptions o;
  o.rays_per_patch = 1 << 15;
  o.seed = 11;
  const FormFactors mc = estimate_form_factors(ps, vis, o);
  const double n = o.rays_per_patch;
  // Entries estimated by rays (entry_std_error > 0) with F_ij >= 0.005 (about 160 expected hits or more: a
  // normal z), two-sample z with se^2 = se_analytic^2 + F (1 - F) / n.
  std::vector<std::tuple<std::string, double, double, double>> cells;
  for (std::size_t i = 0; i < ps.size(); ++i)
    for (Eigen::Index q = F.outerIndexPtr()[i]; q < F.outerIndexPtr()[i + 1]; ++q) {
      const Eigen::Index j = F.innerIndexPtr()[q];
      const double f = F.valuePtr()[q], se_a = a.entry_std_error[std::size_t(q)];
      if (!(se_a > 0) || f < 0.005) continue;
      const double f_mc = entry(mc.F, Eigen::Index(i), j);
      const double se_mc2 = std::max(f_mc * (1 - f_mc), 1.0 / n) / n;
      cells.emplace_back("F_" + std::to_string(i) + "," + std::to_string(j), f, std::sqrt(se_a * se_a + se_mc2), f_mc);
    }
  REQUIRE(cells.size() > 50);
  test::ZTable table("analytic (rays) vs Monte Carlo entries", z_critical(sidak(1e-3, cells.size())));
  for (const auto& c : cells) table.add(std::get<0>(c), std::get<1>(c), std::get<2>(c), std::get<3>(c));
  CHECK(table.check() == 0);

  // Row sums: 1 in the closed room except under the box (and the box's bottom, facing into the floor: 0).
  std::size_t rows = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const double s = row_sum(F, Eigen::Index(i));
    CHECK(s <= 1 + 1e-6);
    if (s > 0) ++rows;
  }
  const double z_rows = z_critical(sidak(1e-3, rows));
  test::ZTable sums("analytic row sums against 1 or the free fraction (closed room)", z_rows);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const double s = row_sum(F, Eigen::Index(i));
    if (s == 0) continue;
    // Every ray of the closed room hits a front, except those into the box's bottom (from under the box): the row
    // sum is 1, or a straddling cell's free fraction, exactly.
    const double expected = free_fraction[i] >= 0 ? free_fraction[i] : 1.0;
    const double se = a.form_factors.row_std_error[i];
    if (se == 0) {  // every pair of the row proven: exact up to float storage
      CHECK(std::abs(s - expected) <= 1e-6);
      continue;
    }
    sums.add("row " + std::to_string(i), s, se, expected);
  }
  CHECK(sums.check() == 0);
}

TEST_CASE("analytic form factors: the same F on 1 and 2 threads, refusal above max_patches", "[formfactor][analytic]") {
  const PatchSet ps = cube_with_box(3, 1);
  const EmbreeVisibility vis(ps);
  AnalyticFormFactors one, two;
  {
    ThreadLimit limit(1);
    one = analytic_form_factors(ps, vis);
  }
  {
    ThreadLimit limit(2);
    two = analytic_form_factors(ps, vis);
  }
  REQUIRE(one.form_factors.F.nonZeros() == two.form_factors.F.nonZeros());
  for (Eigen::Index k = 0; k < one.form_factors.F.nonZeros(); ++k) {
    CHECK(one.form_factors.F.valuePtr()[k] == two.form_factors.F.valuePtr()[k]);
    CHECK(one.form_factors.F.innerIndexPtr()[k] == two.form_factors.F.innerIndexPtr()[k]);
  }
  AnalyticFormFactorOptions o;
  o.max_patches = ps.size() - 1;
  CHECK_THROWS_AS(analytic_form_factors(ps, vis, o), InputError);
}

TEST_CASE("shaft test: clear without an occluder, hidden behind a covering patch, maybe blocked by a small one",
          "[formfactor][analytic]") {
  // Floor [0,1]^2 at z = 0 facing up (patch 0), ceiling at z = 1 facing down (patch 1); then a panel at z = 0.5:
  // [-1, 2]^2 covers every segment, [0.4, 0.6]^2 blocks some; a wall beside the shaft (x = 3) blocks none.
  const auto scene = [](double lo, double hi, bool wall) {
    PatchBuilder b;
    const int grey = b.add_material("grey", Rgb(0.5, 0.5, 0.5));
    b.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, grey);
    b.add_quad({0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}, grey);
    if (hi > lo) b.add_quad({lo, lo, 0.5}, {hi, lo, 0.5}, {hi, hi, 0.5}, {lo, hi, 0.5}, grey);
    if (wall) b.add_quad({3, 0, 0}, {3, 1, 0}, {3, 1, 1}, {3, 0, 1}, grey);
    return b.build();
  };
  const auto classify = [](const PatchSet& ps) {
    ClippedPair pair;
    REQUIRE(clip_patch_pair(ps, 0, 1, pair));
    return PatchShaftTest(ps).classify(0, 1, pair);
  };
  CHECK(classify(scene(0, 0, true)) == ShaftResult::clear);
  CHECK(classify(scene(-1, 2, false)) == ShaftResult::hidden);
  CHECK(classify(scene(0.4, 0.6, true)) == ShaftResult::maybe_blocked);
  // The route: hidden gives no entry, the small panel an estimated one below the unoccluded value.
  const PatchSet small = scene(0.4, 0.6, false);
  const EmbreeVisibility vis(small);
  const AnalyticFormFactors a = analytic_form_factors(small, vis);
  CHECK(a.sampled_pairs >= 1);
  const double unoccluded = test::parallel_rectangles(1, 1, 1);
  CHECK(entry(a.form_factors.F, 0, 1) < unoccluded);
  CHECK(entry(a.form_factors.F, 0, 1) > 0.5 * unoccluded);
  const PatchSet big = scene(-1, 2, false);
  const EmbreeVisibility vis_big(big);
  const AnalyticFormFactors b = analytic_form_factors(big, vis_big);
  CHECK(b.hidden_pairs == 1);
  CHECK(entry(b.form_factors.F, 0, 1) == 0);
}
