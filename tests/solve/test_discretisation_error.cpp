// The discretisation error estimate (solve/discretisation_error.h, docs/theory/discretisation_error.md).
//
// 1. Furnace: a closed unit cube whose patches all emit E = 1 and reflect rho = 0.5 has the constant solution
//    B = 2 in the continuous and the discrete system alike (F exact, rows summing to 1), so the discretisation
//    error is 0. The estimate must be 0 in expectation: over S = 100 seeds the mean of each patch's signed e is
//    z-tested against 0 with its standard error from the seeds' spread (99 degrees of freedom: the normal
//    quantile), Sidak-corrected over the patches at family level 1e-3.
// 2. Calibration against a refined solution: the unit cube with one emitting face, 3 x 3 patches per face, F exact
//    (the analytic route: nothing is occluded); the truth is the 15 x 15 solution averaged over each coarse patch
//    (its own discretisation error is about 3/15 of the coarse one, the error falling as the patch size). The
//    estimate must be sharp: the area-weighted RMS of B_disc over the RMS of the true error lies in [0.5, 2] (the
//    criterion of docs/accuracy.md) at the default 16 directions; and with 256 directions (little noise) the signed
//    estimate must explain the error: the RMS of (true - estimated) is below the RMS of the true error.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <utility>
#include <vector>

#include "formfactor/analytic_form_factors.h"
#include "solve/direct_solver.h"
#include "patch/patch_builder.h"
#include "solve/discretisation_error.h"
#include "solve/fluctuation_source.h"
#include "support/box_scenes.h"
#include "support/statistics.h"
#include "visibility/embree_visibility.h"

using namespace radwalk;

namespace {

struct Solved {
  PatchSet patches;
  RadiosityProblem problem;
  PatchRgb B;
};

// The patches with their exact discrete solution (analytic F, the direct solver).
Solved solved_exactly(PatchSet patches) {
  Solved s;
  s.patches = std::move(patches);
  const EmbreeVisibility visibility(s.patches);
  AnalyticFormFactors ff = analytic_form_factors(s.patches, visibility);
  s.problem = make_problem(s.patches, std::move(ff.form_factors.F));
  s.B = solve_direct(s.problem).B;
  return s;
}

// The unit cube room, k x k patches per face, rho 0.5; E on every patch (furnace) or on the face z = 1 only.
Solved solved_cube(int k, bool furnace) {
  PatchSet patches = test::unit_cube_room(k);
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const bool ceiling = patches.centroid[i].z() > 1 - 1e-9;
    patches.E[i] = furnace || ceiling ? Rgb(1, 1, 1) : Rgb(0, 0, 0);
  }
  return solved_exactly(std::move(patches));
}

}  // namespace

TEST_CASE("discretisation error: the furnace's estimate is 0 in expectation (z-tests over 100 seeds)") {
  const Solved s = solved_cube(3, true);
  const auto N = static_cast<Eigen::Index>(s.patches.size());
  REQUIRE(std::abs(s.B(0, 0) - 2.0) < 1e-6);
  const EmbreeVisibility visibility(s.patches);
  const int seeds = 100;
  Eigen::ArrayXd sum = Eigen::ArrayXd::Zero(N), sum_sq = Eigen::ArrayXd::Zero(N);
  for (int seed = 1; seed <= seeds; ++seed) {
    const DiscretisationError e = discretisation_error(s.patches, visibility, s.problem, s.B, 16, seed);
    sum += e.estimate.col(0);
    sum_sq += e.estimate.col(0).square();
  }
  const double z_crit = z_critical(sidak(1e-3, std::size_t(N)));
  for (Eigen::Index i = 0; i < N; ++i) {
    const double mean = sum[i] / seeds;
    const double se = std::sqrt(std::max(0.0, (sum_sq[i] - seeds * mean * mean) / (seeds - 1)) / seeds);
    INFO("patch " << i << ": mean e " << mean << ", se " << se);
    CHECK(std::abs(mean) <= z_crit * se + 1e-15);
  }
}

TEST_CASE("discretisation error: B_disc is sharp against a 15 x 15 refinement of a cube lit by its ceiling") {
  const Solved coarse = solved_cube(3, false), fine = solved_cube(15, false);
  const auto N = static_cast<Eigen::Index>(coarse.patches.size());
  // The fine solution averaged over each coarse patch (same face: same normal; centroid inside its bounds).
  PatchRgb average = PatchRgb::Zero(N, 3);
  Eigen::ArrayXd area = Eigen::ArrayXd::Zero(N);
  for (std::size_t f = 0; f < fine.patches.size(); ++f)
    for (std::size_t c = 0; c < coarse.patches.size(); ++c) {
      if (fine.patches.normal[f].dot(coarse.patches.normal[c]) < 0.999) continue;
      const Vec3 d = (fine.patches.centroid[f] - coarse.patches.centroid[c]).cwiseAbs();
      if (d.maxCoeff() > 1.0 / 6 + 1e-9) continue;
      average.row(Eigen::Index(c)) += fine.patches.area[f] * fine.B.row(Eigen::Index(f));
      area[Eigen::Index(c)] += fine.patches.area[f];
      break;
    }
  for (Eigen::Index c = 0; c < N; ++c) REQUIRE(std::abs(area[c] - 1.0 / 9) < 1e-9);
  average.colwise() /= area;
  const EmbreeVisibility visibility(coarse.patches);
  const DiscretisationError e = discretisation_error(coarse.patches, visibility, coarse.problem, coarse.B, 16, 1);
  const DiscretisationError precise = discretisation_error(coarse.patches, visibility, coarse.problem, coarse.B, 256, 2);
  double truth2 = 0, estimate2 = 0, residual2 = 0;
  for (Eigen::Index i = 0; i < N; ++i) {
    if (coarse.patches.E[std::size_t(i)].maxCoeff() > 0) continue;  // the emitters' B is their own exact E
    const double t = average(i, 0) - coarse.B(i, 0);
    truth2 += t * t;
    estimate2 += e.standard_error(i, 0) * e.standard_error(i, 0);
    residual2 += (t - precise.estimate(i, 0)) * (t - precise.estimate(i, 0));
  }
  const double sharpness = std::sqrt(estimate2 / truth2);
  INFO("RMS true error " << std::sqrt(truth2 / 45) << ", sharpness " << sharpness << ", RMS of true - estimated "
                         << std::sqrt(residual2 / 45));
  CHECK(sharpness >= 0.5);
  CHECK(sharpness <= 2.0);
  CHECK(residual2 < truth2);
}

// 3. A measurement's discretisation error (measurement_discretisation_error): M = the power reaching the floor
//    (W = A on the face z = 0) of the cube lit by its ceiling, 3 x 3 patches per face. Its signed estimate is the
//    same linear functional of d as the patches' e, so it must equal sum_i W_i e_i of discretisation_error with the
//    same seed and directions (to the two solves' tolerances: e by Jacobi sweeps to a relative change of 1e-6, the
//    adjoint to 1e-10; the bound below is 1e-5 of sum_i |W_i e_i|, ten times that). Against the 15 x 15 truth,
//    with 256 directions the estimate explains the error (|truth - eps| below |truth|), and at the default 16
//    directions the truth lies within 2.5 M_disc.
TEST_CASE("discretisation error: a measurement's M_disc is the sum of its patches' e and explains the truth") {
  const Solved coarse = solved_cube(3, false), fine = solved_cube(15, false);
  const auto N = static_cast<Eigen::Index>(coarse.patches.size());
  const auto floor_weights = [](const PatchSet& p) {
    Eigen::VectorXd W = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(p.size()));
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p.centroid[i].z() < 1e-9) W[Eigen::Index(i)] = p.area[i];
    return W;
  };
  const Eigen::VectorXd W = floor_weights(coarse.patches), W_fine = floor_weights(fine.patches);
  const EmbreeVisibility visibility(coarse.patches);
  const DiscretisationError e = discretisation_error(coarse.patches, visibility, coarse.problem, coarse.B, 16, 7);
  const MeasurementDiscretisationError m =
      measurement_discretisation_error(coarse.patches, visibility, coarse.problem, coarse.B, W, 16, 7);
  double sum = 0, scale = 0;
  for (Eigen::Index i = 0; i < N; ++i) sum += W[i] * e.estimate(i, 0), scale += std::abs(W[i] * e.estimate(i, 0));
  INFO("eps " << m.estimate(0) << ", sum W e " << sum << ", sum |W e| " << scale);
  CHECK(std::abs(m.estimate(0) - sum) <= 1e-5 * scale);

  const double M_coarse = (W.array() * coarse.B.col(0)).sum(), M_fine = (W_fine.array() * fine.B.col(0)).sum();
  const double truth = M_fine - M_coarse;
  const MeasurementDiscretisationError precise =
      measurement_discretisation_error(coarse.patches, visibility, coarse.problem, coarse.B, W, 256, 8);
  INFO("M " << M_coarse << ", truth " << truth << ", eps(256) " << precise.estimate(0) << ", M_disc(16) "
            << m.standard_error(0));
  CHECK(std::abs(truth - precise.estimate(0)) < std::abs(truth));
  CHECK(std::abs(truth) <= 2.5 * m.standard_error(0));
}

// The points of the fluctuation source have one density over the scene (solve/fluctuation_source.h): M = 4 on a
// patch of the median area and s^2 with s = round(2 sqrt(A / A_median)), at most 8, on a larger one. A unit-cube
// room (six faces of area 1, the ceiling emitting) with a box of side 0.2 on its floor cut into 3 x 3 patches per
// face (54 patches of area 0.0044, the median): the room's faces get s = 8 (64 points), the box's 4, so the rays
// are 2 replicates x M x 3 L (cosine gather, shadow rays to the emitter, shot) summed over the patches. With 4
// points everywhere (the large faces' dark spots under the box would then be hit by a point in about one run in
// six) they would be 60 x 24 L. That is without the near-field refinement; with it (the default) each patch adds
// its pilot and may take more points per side and shot directions.
TEST_CASE("discretisation error: the fluctuation's points have one density over the scene") {
  const PatchSet patches = test::room_with_box_on_floor();
  REQUIRE(patches.size() == 60);
  const EmbreeVisibility visibility(patches);
  const PatchRgb B = PatchRgb::Constant(60, 3, 0.5);
  const int L = 4;
  const FluctuationSource source = fluctuation_source(patches, visibility, B, L, 7, 4, false, false);
  CHECK(source.points == 4);
  CHECK(source.rays == 6 * (2 * 64 * 3 * L) + 54 * (2 * 4 * 3 * L));
  // With the near field (the default) every patch first traces a pilot of (s_j^2 + 4 s_j) L rays (its s_j x s_j
  // points and s_j along each of its 4 edges), and those whose pilot reached thinner patches within their points'
  // spacing (here: the room's faces, whose spacing 1/8 exceeds the box's patches' width 0.067) shoot from n_j^2
  // points a replicate instead (n_j up to 16 a side), each with its gather (2 L rays: the cosine gather and the
  // shadow rays to the emitter), L shots and one shadow ray per near target.
  const FluctuationSource refined = fluctuation_source(patches, visibility, B, L, 7, 4, true);
  long rays = 0, near = 0;
  for (std::size_t j = 0; j < 60; ++j) {
    const int own = j < 6 ? 8 : 2;
    const long targets = long(refined.near_targets[j].size());
    INFO("patch " << j << ": " << refined.sides[j] << " points a side, " << targets << " near targets");
    CHECK((targets == 0 ? refined.sides[j] == own : (refined.sides[j] > own && refined.sides[j] <= 16)));
    CHECK(std::is_sorted(refined.near_targets[j].begin(), refined.near_targets[j].end()));
    const long n2 = long(refined.sides[j]) * refined.sides[j];
    rays += (own * own + 4 * own) * L + (targets > 0 ? 2 * n2 * (3 * L + targets) : 2L * own * own * 3 * L);
    near += targets > 0;
  }
  CHECK(refined.rays == rays);
  CHECK(refined.near_field_patches == near);
  CHECK(refined.near_field_patches > 0);
}

// 4. The near field (solve/fluctuation_source.h): a unit room (rho 0.7, cells of 0.1) lit by a light set into the
//    wall x = 0 just above the floor (y in [0.02, 0.1], z in [0.46, 0.54], E = 50: the spot-lit room at 1/500
//    scale). The floor beside that wall is dark at the wall (it sees the light edge-on) and bright a few hundredths
//    out; the wall's band K under the light (y < 0.005) sees mostly the floor within a few K heights of the wall, so
//    the floor patch S beside it (x < 0.025), constant in the discrete solution, makes K read far too bright. The
//    truth: the same room with S cut into 50 strips along x (K's B there is the average over K of what it gathers
//    with S resolved), e_true = Bbar - B_h per coarse patch and d_true = (I - H) e_true (the exact equation
//    Bbar = E + H Bbar + d). Over 40 seeds: S has a near field (its pilot sees the wall within its spacing); the
//    estimate of d_K covers d_true (at most 3 seeds off by more than 3 of its own standard errors: with a correct
//    standard error and a normal estimate the chance of 4 or more is about 5e-6); and its squared error is smaller
//    than without the refinement (the same seeds), one-sided at alpha 0.05.
namespace {

// The unit room with the light in the wall x = 0; the floor's cell S = [0, 0.025] x [0.46, 0.54] cut into `strips`
// strips along x. Patches: K first (the wall x = 0, y in [0, 0.005], z in [0.46, 0.54]), then S's strips.
Solved near_field_room(int strips) {
  PatchBuilder b;
  const int white = b.add_material("white", Rgb(0.7, 0.7, 0.7));
  const int light = b.add_material("light", Rgb(0, 0, 0), Rgb(50, 50, 50));
  // An axis-aligned rectangle of the plane p[f] = at, spanning [u0, u1] x [v0, v1] in the axes u = (f + 1) % 3,
  // v = (f + 2) % 3, its normal +e_f (or -e_f when `flip`).
  auto rect = [&](int f, double at, bool flip, double u0, double u1, double v0, double v1, int material) {
    const int u = (f + 1) % 3, v = (f + 2) % 3;
    std::array<Vec3, 4> q;
    const double us[4] = {u0, u1, u1, u0}, vs[4] = {v0, v0, v1, v1};
    for (int r = 0; r < 4; ++r) {
      Vec3 p;
      p[f] = at, p[u] = us[r], p[v] = vs[r];
      q[flip ? 3 - r : r] = p;
    }
    b.add_quad(q[0], q[1], q[2], q[3], material);
  };
  // Cells of 0.1 elsewhere (as the spot-lit room's 50 mm patches), with the breaks around the light and S.
  auto breaks = [](std::vector<double> extra) {
    for (int t = 0; t <= 10; ++t) extra.push_back(t / 10.0);
    std::sort(extra.begin(), extra.end());
    extra.erase(std::unique(extra.begin(), extra.end()), extra.end());
    return extra;
  };
  std::vector<double> z = breaks({0.46, 0.54});
  z.erase(std::find(z.begin(), z.end(), 0.5));  // K, S and the light span [0.46, 0.54]
  const std::vector<double> tenths = breaks({}), wall_y = breaks({0.005, 0.02}), floor_x = breaks({0.025});
  auto is_mid = [&](std::size_t c) { return z[c] == 0.46; };
  rect(0, 0, false, 0, 0.005, 0.46, 0.54, white);  // K (f = 0: u = y, v = z)
  for (int s = 0; s < strips; ++s)                  // S (f = 1: u = z, v = x)
    rect(1, 0, false, 0.46, 0.54, 0.025 * s / strips, 0.025 * (s + 1) / strips, white);
  for (std::size_t a = 0; a + 1 < wall_y.size(); ++a)
    for (std::size_t c = 0; c + 1 < z.size(); ++c) {
      if (a == 0 && is_mid(c)) continue;  // K
      rect(0, 0, false, wall_y[a], wall_y[a + 1], z[c], z[c + 1], wall_y[a] == 0.02 && is_mid(c) ? light : white);
    }
  for (std::size_t c = 0; c + 1 < z.size(); ++c)
    for (std::size_t a = 0; a + 1 < floor_x.size(); ++a)
      if (!(a == 0 && is_mid(c))) rect(1, 0, false, z[c], z[c + 1], floor_x[a], floor_x[a + 1], white);
  for (std::size_t a = 0; a + 1 < tenths.size(); ++a)
    for (std::size_t c = 0; c + 1 < tenths.size(); ++c) {
      const double u0 = tenths[a], u1 = tenths[a + 1], v0 = tenths[c], v1 = tenths[c + 1];
      rect(0, 1, true, u0, u1, v0, v1, white);   // x = 1
      rect(1, 1, true, u0, u1, v0, v1, white);   // the ceiling y = 1
      rect(2, 0, false, u0, u1, v0, v1, white);  // z = 0 (f = 2: u = x, v = y)
      rect(2, 1, true, u0, u1, v0, v1, white);   // z = 1
    }
  return solved_exactly(b.build());
}

}  // namespace

TEST_CASE("discretisation error: a small patch beside a large one sees its near field resolved") {
  const int strips = 50;
  const Solved coarse = near_field_room(1), fine = near_field_room(strips);
  const auto N = static_cast<Eigen::Index>(coarse.patches.size());
  REQUIRE(static_cast<Eigen::Index>(fine.patches.size()) == N + strips - 1);
  // Bbar per coarse patch: S is the area average of its strips (patches 1 .. strips of fine); the others are the
  // same patches, shifted by strips - 1.
  Eigen::VectorXd e_true(N);
  for (Eigen::Index i = 0; i < N; ++i) {
    double Bbar = 0;
    if (i == 1) {
      for (int s = 1; s <= strips; ++s) Bbar += fine.B(s, 0) / strips;
    } else {
      Bbar = fine.B(i == 0 ? 0 : i + strips - 1, 0);
    }
    e_true[i] = Bbar - coarse.B(i, 0);
  }
  double He = 0;  // (H e_true)_K
  for (SparseF::InnerIterator it(coarse.problem.F, 0); it; ++it) He += double(it.value()) * e_true[it.col()];
  const double d_true = e_true[0] - coarse.problem.rho(0, 0) * He;
  const EmbreeVisibility visibility(coarse.patches);
  const int seeds = 40;
  int off = 0;
  std::vector<double> gain;  // per seed: the squared error of d_K without the refinement minus with it
  std::ostringstream seen;
  long refined = 0;
  for (std::uint64_t seed = 1; seed <= seeds; ++seed) {
    const FluctuationSource with = fluctuation_source(coarse.patches, visibility, coarse.B, 16, seed);
    const FluctuationSource without =
        fluctuation_source(coarse.patches, visibility, coarse.B, 16, seed, 4, false, false);
    const double sd = std::sqrt(with.variance(0, 0));
    off += std::abs(with.d(0, 0) - d_true) > 3 * sd;
    gain.push_back(std::pow(without.d(0, 0) - d_true, 2) - std::pow(with.d(0, 0) - d_true, 2));
    refined += with.sides[1] > 2;
    CHECK(without.near_field_patches == 0);
    seen << " " << with.d(0, 0) << " +- " << sd << " (" << without.d(0, 0) << ");";
  }
  double mean_gain = 0, spread = 0;
  for (double g : gain) mean_gain += g / seeds;
  for (double g : gain) spread += (g - mean_gain) * (g - mean_gain) / (seeds - 1);
  const double se_gain = std::sqrt(spread / seeds);
  INFO("K: B_h " << coarse.B(0, 0) << ", Bbar " << coarse.B(0, 0) + e_true[0] << ", d_true " << d_true
                 << "; S refined on " << refined << " seeds; d_K (without the refinement):" << seen.str()
                 << "; mean gain in squared error " << mean_gain << " +- " << se_gain);
  CHECK(refined == seeds);
  CHECK(off <= 3);
  // One-sided z-test of the mean gain at alpha 0.05 (39 degrees of freedom: about the normal quantile). The squared
  // errors are heavy-tailed (the unrefined estimate's occasional -5 to -6 for -2), so the test has little power at a
  // smaller alpha: measured 1.37 +- 0.55 (z = 2.5).
  CHECK(mean_gain > z_critical(0.1) * se_gain);
}

// 5. The empirical-Bayes prior's size classes (prior_classes): levels of area by factors of 4 from the largest,
//    joined until a class holds kPriorClassPatches; uncounted patches take the class nearest in area.
TEST_CASE("discretisation error: the prior is fitted per size class of at least 64 patches") {
  const auto classes_of = [](const std::vector<double>& area, std::vector<bool> counted = {}) {
    if (counted.empty()) counted.assign(area.size(), true);
    return prior_classes(area, counted);
  };
  SECTION("a uniform patching, or one with pieces within a factor 4: one class") {
    std::vector<double> area(500, 1.0);
    for (std::size_t i = 0; i < 100; ++i) area[i] = 0.3;
    const PriorClasses c = classes_of(area);
    CHECK(c.count == 1);
    CHECK(std::all_of(c.of.begin(), c.of.end(), [](std::size_t x) { return x == 0; }));
  }
  SECTION("fewer than 2 x 64 counted patches: one class, however their sizes differ") {
    std::vector<double> area(127);
    for (std::size_t i = 0; i < area.size(); ++i) area[i] = std::pow(0.5, double(i % 10));
    CHECK(classes_of(area).count == 1);
  }
  SECTION("a hierarchy's levels: 100 leaves of area 1, 100 of 1/16, 10 of 1/256 (joining the class before)") {
    std::vector<double> area;
    for (int i = 0; i < 100; ++i) area.push_back(1.0), area.push_back(1.0 / 16);
    for (int i = 0; i < 10; ++i) area.push_back(1.0 / 256);
    std::vector<bool> counted(area.size(), true);
    area.push_back(0.5), counted.push_back(false);   // an emitter as large as level 0
    area.push_back(1e-6), counted.push_back(false);  // a black sliver smaller than any
    const PriorClasses c = classes_of(area, counted);
    REQUIRE(c.count == 2);
    for (std::size_t i = 0; i < 200; ++i) CHECK(c.of[i] == (i % 2 == 0 ? 0u : 1u));
    for (std::size_t i = 200; i < 210; ++i) CHECK(c.of[i] == 1u);
    CHECK(c.of[210] == 0u);
    CHECK(c.of[211] == 1u);
  }
}
