// The shooter attribution of the discretisation error (solve/shooter_attribution.h) and the refinement marks that
// use it (solve/refinement_marks.h); docs/theory/discretisation_error.md, "Which patch causes the error".
//
// 1. The identity: on the unit cube lit by its ceiling (3 x 3 patches a face, F exact), the shares sum to
//    sum_{i,c} A_i e^(0)_ic e^(1)_ic, with e^(r) = (I - H)^{-1} d^(r) solved here independently by dense LU from the
//    replicates of fluctuation_source (same arguments): a relative difference below 1e-5 (the Jacobi tolerances are
//    1e-7, the error of a sweep's fixed point 1e-7 / (1 - rho); the shots are summed in another order). Deterministic: not a hypothesis test. 1 and 2 threads give the
//    same shares bit for bit.
// 2. No bias where nothing fluctuates: in the furnace (every patch emits 1 and reflects 0.5: B = 2 everywhere, in
//    the continuous and the discrete system) every shooter's true share is 0. Over S = 60 seeds the mean c_j of each
//    patch is z-tested against 0 (standard error from the seeds' spread, 59 degrees of freedom: the normal quantile
//    with a Student margin below 0.1 at these levels), Sidak-corrected over the 54 patches at family level 1e-3. The
//    same test rejects the product of one replicate's adjoint with its own shots (the noise squared, a positive
//    bias), which is what the cross-replicate product avoids: shown on the sum over the patches.
// 3. The spot-lit room at --max-edge 50 (scripts/experiments/scenes/spot_room.obj: a light on the wall x = 0, 10 to
//    50 mm above the floor; docs/hierarchy.md, the strip): the floor patches beside the light's wall shoot the
//    error of the 10 mm wall strip below the light. With a split fraction of 1/2, in each of S = 4 seeds the receiver
//    rule alone marks none of them and the combined rule marks at least one. That this is not chance is a test at
//    1e-3: under H0 the combined rule's m_s marks of seed s fall on these n patches no more often than m_s patches
//    drawn at random, p_s = 1 - (1 - m_s / N)^n, and the probability of the S seeds' outcome is prod_s p_s < 1e-3.
//    (Each c_j alone is noisy at 16 directions: the sum of these patches' shares varied from -1850 to +2800 over
//    the seeds, around a total of the same size, so its sign is not tested.) Against the old indicator (the
//    receiver rule) this case fails.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "core/parallel.h"
#include "formfactor/analytic_form_factors.h"
#include "formfactor/emitter_form_factors.h"
#include "mesh/read_scene.h"
#include "patch/patching.h"
#include "solve/block_jacobi.h"
#include "solve/direct_solver.h"
#include "solve/discretisation_error.h"
#include "solve/fluctuation_source.h"
#include "solve/refinement_marks.h"
#include "solve/shooter_attribution.h"
#include "solve/solve_radiosity.h"
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

// The room with a box on its floor (support/box_scenes.h): its faces have near targets.
Solved solved_room_with_box() {
  Solved s;
  s.patches = test::room_with_box_on_floor();
  const EmbreeVisibility visibility(s.patches);
  AnalyticFormFactors ff = analytic_form_factors(s.patches, visibility);
  s.problem = make_problem(s.patches, std::move(ff.form_factors.F));
  s.B = solve_direct(s.problem).B;
  return s;
}

double sum_of(const std::vector<double>& v) {
  double s = 0;
  for (const double x : v) s += x;
  return s;
}

}  // namespace

TEST_CASE("shooter attribution: the shares sum to sum_i A_i e0_i . e1_i (dense LU of both replicates), for any thread count") {
  // The cube in 3 x 3 patches a face, and a room whose faces reach their near targets through F_vis (the replay of
  // those terms must give the same numbers as the source's).
  const bool with_box = GENERATE(false, true);
  INFO((with_box ? "the room with a box" : "the cube"));
  const Solved s = with_box ? solved_room_with_box() : solved_cube(3, false);
  const EmbreeVisibility visibility(s.patches);
  const auto N = static_cast<Eigen::Index>(s.patches.size());
  const int L = 16;
  const std::uint64_t seed = 7;
  ShooterAttribution a;
  discretisation_error(s.patches, visibility, s.problem, s.B, L, seed, &a);
  REQUIRE(a.share.size() == s.patches.size());
  const FluctuationSource source = fluctuation_source(s.patches, visibility, s.B, L, seed);
  CHECK((source.near_field_patches > 0) == with_box);
  const Eigen::MatrixXd F = Eigen::MatrixXd(s.problem.F.cast<double>());
  double expected = 0, size = 0;
  for (int c = 0; c < 3; ++c) {
    const Eigen::MatrixXd I_H =
        Eigen::MatrixXd::Identity(N, N) - s.problem.rho.col(c).matrix().asDiagonal() * F;
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(I_H);
    const Eigen::VectorXd e0 = lu.solve(source.replicate[0].col(c).matrix());
    const Eigen::VectorXd e1 = lu.solve(source.replicate[1].col(c).matrix());
    for (Eigen::Index i = 0; i < N; ++i) {
      expected += s.patches.area[static_cast<std::size_t>(i)] * e0[i] * e1[i];
      size += s.patches.area[static_cast<std::size_t>(i)] * std::abs(e0[i] * e1[i]);
    }
  }
  INFO("sum c_j " << sum_of(a.share) << ", sum A e0 e1 " << expected << ", reported total " << a.total);
  REQUIRE(size > 0);
  CHECK(std::abs(sum_of(a.share) - expected) <= 1e-5 * size);
  CHECK(std::abs(a.total - expected) <= 1e-5 * size);
  // Reproducible: 1 and 2 threads give the same shares bit for bit.
  ShooterAttribution one, two;
  {
    const ThreadLimit limit(1);
    discretisation_error(s.patches, visibility, s.problem, s.B, L, seed, &one);
  }
  {
    const ThreadLimit limit(2);
    discretisation_error(s.patches, visibility, s.problem, s.B, L, seed, &two);
  }
  CHECK(one.share == two.share);
  CHECK(one.share == a.share);
}

TEST_CASE("shooter attribution: in the furnace every share is 0 in expectation (z-tests over 60 seeds), and the "
          "same-replicate product is biased") {
  const Solved s = solved_cube(3, true);
  REQUIRE(std::abs(s.B(0, 0) - 2.0) < 1e-6);
  const EmbreeVisibility visibility(s.patches);
  const std::size_t N = s.patches.size();
  const int seeds = 60, L = 16;
  std::vector<double> sum(N, 0.0), sum_sq(N, 0.0);
  double own_sum = 0, own_sq = 0, cross_sum = 0, cross_sq = 0;
  for (int seed = 1; seed <= seeds; ++seed) {
    ShooterAttribution a;
    discretisation_error(s.patches, visibility, s.problem, s.B, L, seed, &a);
    REQUIRE(a.share.size() == N);
    for (std::size_t j = 0; j < N; ++j) sum[j] += a.share[j], sum_sq[j] += a.share[j] * a.share[j];
    const double total = sum_of(a.share);
    cross_sum += total, cross_sq += total * total;
    // The deliberately wrong estimate: each replicate's shots weighted by its own adjoint.
    const FluctuationSource source = fluctuation_source(s.patches, visibility, s.B, L, seed, 4, true);
    const auto n = static_cast<Eigen::Index>(N);
    RowBlock Z(n, 6);
    for (int r = 0; r < 2; ++r) Z.middleCols(3 * r, 3) = source.replicate[r];
    const BlockSolution e = solve_block_jacobi(s.problem, Z, 1e-10, "test");
    RowBlock W(n, 6);
    for (Eigen::Index i = 0; i < n; ++i) W.row(i) = s.patches.area[static_cast<std::size_t>(i)] * e.X.row(i);
    long sweeps = 0;
    const RowBlock psi = adjoint_block(s.problem, W, sweeps);
    const PatchRgb own[2] = {psi.middleCols(0, 3) / 2, psi.middleCols(3, 3) / 2};
    const double wrong = sum_of(weighted_fluctuation_shots(s.patches, visibility, s.B, source, own, L, seed));
    own_sum += wrong, own_sq += wrong * wrong;
  }
  const double z_crit = z_critical(sidak(1e-3, N));
  for (std::size_t j = 0; j < N; ++j) {
    const double mean = sum[j] / seeds;
    const double se = std::sqrt(std::max(0.0, (sum_sq[j] - seeds * mean * mean) / (seeds - 1)) / seeds);
    INFO("patch " << j << ": mean c " << mean << ", se " << se);
    CHECK(std::abs(mean) <= z_crit * se + 1e-15);
  }
  const auto z_of = [&](double s1, double s2) {
    const double mean = s1 / seeds;
    const double se = std::sqrt(std::max(0.0, (s2 - seeds * mean * mean) / (seeds - 1)) / seeds);
    return mean / se;
  };
  const double z_cross = z_of(cross_sum, cross_sq), z_own = z_of(own_sum, own_sq);
  INFO("z of the summed shares: cross-replicate " << z_cross << ", same replicate " << z_own);
  const double z_sum = z_critical(1e-3);
  CHECK(std::abs(z_cross) <= z_sum);
  CHECK(z_own > z_sum);
}

TEST_CASE("shooter attribution: on the spot-lit room the floor beside the light's wall is marked as the shooter "
          "the receiver rule misses") {
  const PatchSet patches =
      make_patches(load_scene(std::string(RADWALK_SOURCE_DIR) + "/scripts/experiments/scenes/spot_room.obj"), 50.0);
  const EmbreeVisibility visibility(patches);
  const std::size_t N = patches.size();
  // The floor (y = 0, facing +y) patches beside the wall x = 0 in front of the light (z 230 to 270), one patch on
  // either side along z.
  std::vector<std::size_t> beside;
  for (std::size_t i = 0; i < N; ++i) {
    const Vec3& c = patches.centroid[i];
    if (patches.normal[i].y() > 0.99 && std::abs(c.y()) < 1e-9 && c.x() < 50 && c.z() > 180 && c.z() < 320)
      beside.push_back(i);
  }
  REQUIRE(beside.size() >= 3);
  const int seeds = 4;
  double p_random = 1;
  for (int seed = 1; seed <= seeds; ++seed) {
    FormFactorOptions o;
    o.rays_per_patch = 1000;
    o.seed = seed;
    o.sobol = true;
    FormFactors ff = estimate_form_factors_with_emitters(patches, visibility, o, kAutoEmitterSamples);
    const RadiosityProblem problem = make_problem(patches, std::move(ff.F));
    SolveOptions so;
    so.max_iterations = default_max_iterations(so.solver, N);
    const Solution x = solve_radiosity(problem, so);
    REQUIRE(x.status == SolveStatus::converged);
    ShooterAttribution a;
    const DiscretisationError d = discretisation_error(patches, visibility, problem, x.B, 16, seed, &a);
    std::vector<double> receiver(N, 0.0);
    for (std::size_t i = 0; i < N; ++i)
      if (patches.E[i].maxCoeff() <= 0 && patches.rho[i].maxCoeff() > 0)
        receiver[i] = patches.area[i] * d.standard_error.row(static_cast<Eigen::Index>(i)).square().sum();
    const std::vector<bool> old_marks = refinement_marks(receiver, {}, 0.5, 0.0, N);
    const std::vector<bool> new_marks = refinement_marks(receiver, a.share, 0.5, 0.0, N);
    bool old_marked = false, new_marked = false;
    for (const std::size_t i : beside) {
      old_marked = old_marked || old_marks[i];
      new_marked = new_marked || new_marks[i];
      INFO("seed " << seed << " floor patch " << i << " at " << patches.centroid[i].transpose() << ": c "
                   << a.share[i] << " (sum " << sum_of(a.share) << "), receiver " << receiver[i]);
      CHECK(true);
    }
    const auto marked = static_cast<double>(std::count(new_marks.begin(), new_marks.end(), true));
    // H0: the combined rule marks these patches no more often than a pick of `marked` patches at random.
    p_random *= 1 - std::pow(1 - marked / double(N), double(beside.size()));
    INFO("seed " << seed << ": " << marked << " patches marked");
    CHECK_FALSE(old_marked);
    CHECK(new_marked);
  }
  INFO("probability of these marks at random " << p_random);
  CHECK(p_random < 1e-3);
}

TEST_CASE("refinement marks: the union of the two shares' marks, the budget by the larger normalised share") {
  const std::vector<double> receiver = {10, 1, 1, 0}, shooter = {0, 0, 5, -3};
  // Receiver: 10 of 12 holds 1/2. Shooter: 5 of the positive 5 holds 1/2 (the negative share never ranks).
  CHECK(refinement_marks(receiver, {}, 0.5, 0.0, 4) == std::vector<bool>{true, false, false, false});
  CHECK(refinement_marks(receiver, shooter, 0.5, 0.0, 4) == std::vector<bool>{true, false, true, false});
  // Room for one: patch 2 (5 / 5 of the shooters' total) before patch 0 (10 / 12 of the receivers').
  CHECK(refinement_marks(receiver, shooter, 0.5, 0.0, 1) == std::vector<bool>{false, false, true, false});
  // A floor above a share leaves it unmarked; an element that cannot be split is passed over.
  CHECK(refinement_marks(receiver, shooter, 0.5, 6.0, 4) == std::vector<bool>{true, false, false, false});
  CHECK(refinement_marks(receiver, shooter, 0.5, 0.0, 4, {false, true, true, true}) ==
        std::vector<bool>{false, true, true, false});
}
