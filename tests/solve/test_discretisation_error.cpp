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

#include <cmath>
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

// The unit cube room, k x k patches per face, rho 0.5; E on every patch (furnace) or on the face z = 1 only.
Solved solved_cube(int k, bool furnace) {
  Solved s;
  s.patches = test::unit_cube_room(k);
  for (std::size_t i = 0; i < s.patches.size(); ++i) {
    const bool ceiling = s.patches.centroid[i].z() > 1 - 1e-9;
    s.patches.E[i] = furnace || ceiling ? Rgb(1, 1, 1) : Rgb(0, 0, 0);
  }
  const EmbreeVisibility visibility(s.patches);
  AnalyticFormFactors ff = analytic_form_factors(s.patches, visibility);
  s.problem = make_problem(s.patches, std::move(ff.form_factors.F));
  s.B = solve_direct(s.problem).B;
  return s;
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
// six) they would be 60 x 24 L.
TEST_CASE("discretisation error: the fluctuation's points have one density over the scene") {
  PatchBuilder b;
  const int m = b.add_material("white", Rgb(0.5, 0.5, 0.5));
  test::add_box(b, Vec3(0, 0, 0), Vec3(1, 1, 1), 1, true, m);
  test::add_box(b, Vec3(0.4, 0, 0.4), Vec3(0.6, 0.2, 0.6), 3, false, m);
  PatchSet patches = b.build();
  for (std::size_t i = 0; i < patches.size(); ++i)
    patches.E[i] = patches.centroid[i].y() > 1 - 1e-9 ? Rgb(1, 1, 1) : Rgb(0, 0, 0);
  REQUIRE(patches.size() == 60);
  const EmbreeVisibility visibility(patches);
  const PatchRgb B = PatchRgb::Constant(60, 3, 0.5);
  const int L = 4;
  const FluctuationSource source = fluctuation_source(patches, visibility, B, L, 7);
  CHECK(source.points == 4);
  CHECK(source.rays == 6 * (2 * 64 * 3 * L) + 54 * (2 * 4 * 3 * L));
}
