// The statistical error of B from traced form factors (docs/theory/error_estimate.md).
//
// 1. The propagation (solve/error_propagation.h) against the exact diagonal of G diag(q) G^T on a random problem:
//    its estimate q_i + mean_k (x_ik^2 - z_ik^2) is a mean of K independent terms w = 2 z y + y^2 (y = (G - I) z),
//    whose exact mean and variance follow from Isserlis' theorem for the jointly normal (z_i, y_i):
//      E w = 2 c + b,  Var w = 4 a b + 4 c^2 + 8 b c + 2 b^2,   a = q_i, b = sum_j (G - I)_ij^2 q_j, c = (G - I)_ii q_i.
//    z-tests, Sidak-corrected over the 3 N entries at family level 1e-3.
// 2. Coverage: on the closed unit cube (one patch per face, F exact from the closed forms), F traced at 400 rays per
//    patch with 200 seeds, stratified (the default) and independent rays; B_se from F's noise must cover the exact
//    solution: the fraction of (seed, patch) values of channel 0 with |B - B_exact| <= 1.96 B_se is tested against
//    0.95 with its standard error estimated from the per-seed fractions (seeds are independent; patches of one seed
//    are not), two-sided at level 1e-3; and the estimate must be sharp: RMS of B_se over RMS of the error in
//    [0.5, 2].
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "core/rng.h"
#include "formfactor/form_factors.h"
#include "solve/direct_solver.h"
#include "solve/error_propagation.h"
#include "solve/form_factor_error.h"
#include "support/box_scenes.h"
#include "support/reference_problems.h"
#include "support/stat_checks.h"
#include "support/statistics.h"
#include "visibility/embree_visibility.h"

using namespace radwalk;

namespace {

// A random problem: each row of F has 6 entries in other columns summing to 0.9, rho in [0.5, 0.9).
RadiosityProblem random_problem(int N) {
  Rng rng = stream(7, StreamDomain::test, 1, 0);
  std::vector<Eigen::Triplet<float, std::int32_t>> t;
  for (int i = 0; i < N; ++i) {
    std::vector<double> w(6);
    double sum = 0;
    for (double& x : w) sum += (x = 0.1 + rng.uniform());
    for (int k = 0; k < 6; ++k) {
      int j = static_cast<int>(rng.uniform_index(std::uint32_t(N - 1)));
      if (j >= i) ++j;
      t.emplace_back(i, j, static_cast<float>(0.9 * w[k] / sum));
    }
  }
  RadiosityProblem p;
  p.F = SparseF(N, N);
  p.F.setFromTriplets(t.begin(), t.end());  // duplicates are summed: a row still sums to 0.9
  p.rho.resize(N, 3);
  p.E = PatchRgb::Zero(N, 3);
  for (int i = 0; i < N; ++i)
    for (int c = 0; c < 3; ++c) p.rho(i, c) = 0.5 + 0.4 * rng.uniform();
  p.area = Eigen::VectorXd::Ones(N);
  return p;
}

}  // namespace

TEST_CASE("the propagated variance of B is the diagonal of G diag(rho^2 V) G^T within its probe noise") {
  const int N = 24, K = 256;
  const RadiosityProblem p = random_problem(N);
  Rng rng = stream(8, StreamDomain::test, 2, 0);
  PatchRgb V(N, 3);
  for (int i = 0; i < N; ++i)
    for (int c = 0; c < 3; ++c) V(i, c) = rng.uniform() * (i % 5 == 0 ? 0.0 : 1.0);  // some rows without noise
  const PropagatedVariance result = propagate_gather_variance(p, V, K, 11);
  REQUIRE(result.probes == K);
  const double z_crit = z_critical(sidak(1e-3, 3 * N));
  test::ZTable table("propagated variance against the dense formula", z_crit);
  const Eigen::MatrixXd F = Eigen::MatrixXd(p.F.cast<double>());
  for (int c = 0; c < 3; ++c) {
    const Eigen::VectorXd q = (p.rho.col(c).square() * V.col(c)).matrix();
    const Eigen::MatrixXd G = (Eigen::MatrixXd::Identity(N, N) - p.rho.col(c).matrix().asDiagonal() * F).inverse();
    const Eigen::MatrixXd Gm = G - Eigen::MatrixXd::Identity(N, N);
    for (int i = 0; i < N; ++i) {
      const double exact = (G.row(i).array().square() * q.transpose().array()).sum();
      const double a = q[i], b = (Gm.row(i).array().square() * q.transpose().array()).sum(), cc = Gm(i, i) * q[i];
      const double var_w = 4 * a * b + 4 * cc * cc + 8 * b * cc + 2 * b * b;
      CHECK(result.variance(i, c) >= q[i]);
      table.add_patch(i, c, "Var(B) patch " + std::to_string(i) + " channel " + std::to_string(c),
                      result.variance(i, c), std::sqrt(var_w / K), exact);
    }
  }
  CHECK(table.check() == 0);
}

TEST_CASE("B_se from the form factors' noise covers the exact solution of the unit cube 95 % of the time") {
  PatchSet patches = test::unit_cube_room(1);
  // One emitting face; the others reflect with different rho.
  const double rho[6] = {0.3, 0.5, 0.6, 0.7, 0.8, 0.4};
  for (std::size_t i = 0; i < 6; ++i) {
    patches.rho[i] = Rgb::Constant(rho[i]);
    patches.E[i] = Rgb::Constant(i == 0 ? 10.0 : 0.0);
  }
  const EmbreeVisibility visibility(patches);
  PatchRgb rho_rows(6, 3), E_rows(6, 3);
  for (int i = 0; i < 6; ++i) {
    rho_rows.row(i) = patches.rho[std::size_t(i)].transpose();
    E_rows.row(i) = patches.E[std::size_t(i)].transpose();
  }
  const RadiosityProblem exact = test::cube_problem(rho_rows, E_rows);
  const PatchRgb B_exact = solve_direct(exact).B;
  const int seeds = 200;
  for (const bool stratified : {true, false}) {
    DYNAMIC_SECTION((stratified ? "stratified rays" : "independent rays")) {
      std::vector<double> fraction;
      double error2 = 0, se2 = 0;
      for (int s = 1; s <= seeds; ++s) {
        FormFactorOptions o;
        o.rays_per_patch = 400;
        o.seed = std::uint64_t(s);
        o.stratified = stratified;
        FormFactors ff = estimate_form_factors(patches, visibility, o);
        RadiosityProblem p = make_problem(patches, ff.F);
        const PatchRgb B = solve_direct(p).B;
        const FormFactorError error = form_factor_error(patches, visibility, ff, p, B);
        if (!stratified) CHECK(error.calibration.factors.rays == 1.0);
        int inside = 0, count = 0;
        for (int i = 1; i < 6; ++i) {
          const double d = B(i, 0) - B_exact(i, 0), se = error.standard_error(i, 0);
          inside += std::abs(d) <= 1.96 * se;
          ++count;
          error2 += d * d;
          se2 += se * se;
        }
        fraction.push_back(double(inside) / count);
      }
      double mean = 0, var = 0;
      for (double f : fraction) mean += f / seeds;
      for (double f : fraction) var += (f - mean) * (f - mean) / (seeds - 1);
      INFO("coverage " << mean << " over " << seeds << " seeds; sharpness " << std::sqrt(se2 / error2));
      test::check_z("coverage of 1.96 B_se", mean, std::sqrt(var / seeds), 0.95, z_critical(1e-3));
      const double sharpness = std::sqrt(se2 / error2);
      CHECK(sharpness >= 0.5);
      CHECK(sharpness <= 2.0);
    }
  }
}
