// Exact variances (walk_variance.h) against empirical per-walk variances (variance z-test with the sample fourth
// moment, support/statistics.h), family-wise alpha = 1e-3 with Sidak; the furnace and non-reflecting-emitter facts of
// docs/reference-data.md ("Random-walk estimator facts"); and the finite-variance check.
#include <catch2/catch.hpp>

#include "core/moments.h"
#include "support/stat_checks.h"
#include "walk/matrix_kernel.h"
#include "walk/random_walk_solver.h"
#include "walk/walk_variance.h"
#include "walk_test_scenes.h"

using namespace radwalk;

namespace {

// Variance z-test of per-walk samples x against var_true; zero-variance cases must be zero up to rounding.
bool variance_matches(const std::vector<double>& x, double var_true, double scale2, double z_crit,
                      const std::string& label) {
  const SampleMoments m = sample_moments(x);
  if (var_true <= 1e-14 * scale2) {
    if (m.var <= 1e-14 * scale2) return true;
    WARN(label << ": theory 0 but sample variance " << m.var);
    return false;
  }
  const double z = variance_z_score(m.var, var_true, m.mu4, m.n);
  if (std::abs(z) <= z_crit) return true;
  WARN(label << ": sample variance " << m.var << ", theory " << var_true << ", z = " << z << ", critical "
                      << z_crit);
  return false;
}

struct Case {
  std::string name;
  RadiosityProblem problem;
  Survival survival;
};

}  // namespace

TEST_CASE("empirical per-walk variances match the exact ones", "[walk][variance]") {
  std::vector<Case> cases = {
      {"closed cube, analog", test::mixed_cube(), {SurvivalRule::analog}},
      {"open cube, analog", test::mixed_cube({0, 1, 2, 3, 4}), {SurvivalRule::analog}},
      {"closed cube, survival max", test::mixed_cube(), {SurvivalRule::max}},
      {"closed cube, unequal areas, row 0 x 1.05 (not reciprocal)", test::mixed_cube(), {SurvivalRule::analog}}};
  cases.back().problem.area << 1, 1.1, 0.9, 1.05, 0.95, 1.0;  // mild: T rows sum to 1 +- 0.1, finite 4th moments
  for (SparseF::InnerIterator it(cases.back().problem.F, 0); it; ++it) it.valueRef() *= 1.05f;
  std::size_t checks = 0;
  for (const Case& c : cases) checks += kWalkMethods.size() * c.problem.size() * 3;
  const double z_crit = z_critical(sidak(1e-3, checks));
  int failed = 0;
  for (const Case& c : cases) {
    const RadiosityProblem& p = c.problem;
    const PatchRgb B = dense_radiosity(p);
    const MatrixKernel kernel(p, survival_probabilities(p.rho, c.survival));
    const MatrixKernel shoot_kernel(p, survival_probabilities(p.rho, c.survival), WalkDirection::shoot);
    for (const WalkMethod method : all_walk_methods()) {
      WalkOptions o;
      o.method = method;
      o.survival = c.survival;
      const PatchRgb theory = theoretical_variance(p, o, B);
      const std::string label = c.name + ", " + std::string(method_name(method));
      if (is_gathering(method)) {
        for (std::size_t i = 0; i < p.size(); ++i) {
          const auto x = test::gather_scores(method, kernel, i, 100000, 5);
          for (int ch = 0; ch < 3; ++ch) {
            const double b = B(static_cast<Eigen::Index>(i), ch);
            failed += !variance_matches(x[ch], theory(static_cast<Eigen::Index>(i), ch), b * b, z_crit,
                                        label + " patch " + std::to_string(i) + " ch " + std::to_string(ch));
          }
        }
      } else {
        const auto y = test::shoot_scores(method, shoot_kernel, p, 200000, 5);
        for (std::size_t j = 0; j < p.size(); ++j)
          for (int ch = 0; ch < 3; ++ch) {
            const double b = B(static_cast<Eigen::Index>(j), ch);
            failed += !variance_matches(y[j * 3 + ch], theory(static_cast<Eigen::Index>(j), ch), b * b, z_crit,
                                        label + " patch " + std::to_string(j) + " ch " + std::to_string(ch));
          }
      }
    }
  }
  CHECK(failed == 0);
}

TEST_CASE("the variance test rejects a wrong variance", "[walk][variance]") {
  // Collision samples tested against the absorption theory (different by a factor of several here).
  const RadiosityProblem p = test::mixed_cube();
  const PatchRgb B = dense_radiosity(p);
  const MatrixKernel kernel(p, survival_probabilities(p.rho, {}));
  WalkOptions o;
  o.method = WalkMethod::gather_absorption;
  const PatchRgb wrong = theoretical_variance(p, o, B);
  const auto x = test::gather_scores(WalkMethod::gather_collision, kernel, 1, 100000, 5);
  const SampleMoments m = sample_moments(x[0]);
  INFO("collision sample variance " << m.var << " vs absorption theory " << wrong(1, 0));
  CHECK(std::abs(variance_z_score(m.var, wrong(1, 0), m.mu4, m.n)) > z_critical(1e-3));
}

TEST_CASE("furnace: absorption has zero variance, collision E^2 rho / (1 - rho)^2", "[walk][variance][furnace]") {
  const double rho = 0.6;
  PatchRgb R = PatchRgb::Constant(6, 3, rho), E(6, 3);
  for (Eigen::Index i = 0; i < 6; ++i) E.row(i) << 1.0, 2.0, 3.0;
  RadiosityProblem p = test::cube_problem(R, E);
  // Rows of the float F may sum to 1 + 1e-7 (row scale n > 1, weights n != 1): lower the opposite-face entry to
  // the largest float that keeps each row sum <= 1, so the analog weights are exactly 1.
  for (Eigen::Index k = 0; k < 6; ++k) {
    double sum = 0;
    for (SparseF::InnerIterator it(p.F, k); it; ++it) sum += it.value();
    for (SparseF::InnerIterator it(p.F, k); it; ++it)
      if (it.col() == (k ^ 1))
        while (sum > 1.0) {
          const float lower = std::nextafter(it.value(), 0.0f);
          sum -= double(it.value()) - double(lower);
          it.valueRef() = lower;
        }
  }
  const PatchRgb B = dense_radiosity(p);
  WalkOptions o;
  o.method = WalkMethod::gather_absorption;
  o.walks_per_patch = 50000;
  o.theory = true;
  // Absorption: every walk scores E / q exactly (float F rows sum to 1 up to 1e-7).
  const Solution a = solve_random_walk(p, nullptr, nullptr, o);
  for (Eigen::Index i = 0; i < 6; ++i)
    for (int c = 0; c < 3; ++c) {
      CHECK(a.var(i, c) == 0.0);
      CHECK(a.B(i, c) == Approx(E(i, c) / (1 - rho)).epsilon(1e-6));
      CHECK(std::abs(a.var_theory(i, c)) <= 1e-9 * B(i, c) * B(i, c));
    }
  // Collision: theory equals the closed form; the sample variance passes the variance z-test (Sidak over 18).
  o.method = WalkMethod::gather_collision;
  const PatchRgb theory = theoretical_variance(p, o, B);
  const MatrixKernel kernel(p, survival_probabilities(p.rho, {}));
  const double z_crit = z_critical(sidak(1e-3, 18));
  for (std::size_t i = 0; i < 6; ++i) {
    const auto x = test::gather_scores(WalkMethod::gather_collision, kernel, i, 50000, 3);
    for (int c = 0; c < 3; ++c) {
      const double closed_form = E(0, c) * E(0, c) * rho / ((1 - rho) * (1 - rho));
      CHECK(theory(static_cast<Eigen::Index>(i), c) == Approx(closed_form).epsilon(1e-6));
      const SampleMoments m = sample_moments(x[c]);
      const double z = variance_z_score(m.var, closed_form, m.mu4, m.n);
      INFO("patch " << i << " channel " << c << ": sample variance " << m.var << ", closed form " << closed_form);
      CHECK(std::abs(z) <= z_crit);
    }
  }
}

TEST_CASE("non-reflecting emitters: absorption and collision have identical variance", "[walk][variance]") {
  // Face 0 emits and reflects nothing; the others reflect and emit nothing.
  PatchRgb R(6, 3), E = PatchRgb::Zero(6, 3);
  R << 0.0, 0.0, 0.0,  0.5, 0.4, 0.6,  0.7, 0.5, 0.3,  0.6, 0.6, 0.6,  0.4, 0.5, 0.2,  0.3, 0.7, 0.5;
  E.row(0) << 10.0, 6.0, 3.0;
  const RadiosityProblem p = test::cube_problem(R, E);
  const PatchRgb B = dense_radiosity(p);
  WalkOptions a, c;
  a.method = WalkMethod::gather_absorption;
  c.method = WalkMethod::gather_collision;
  const PatchRgb va = theoretical_variance(p, a, B), vc = theoretical_variance(p, c, B);
  for (Eigen::Index i = 0; i < 6; ++i)
    for (int ch = 0; ch < 3; ++ch) CHECK(va(i, ch) == Approx(vc(i, ch)).epsilon(1e-10).margin(1e-12));
  // Empirically: with the same streams every walk scores the same under both; each matches the theory.
  a.walks_per_patch = c.walks_per_patch = 50000;
  const Solution sa = solve_random_walk(p, nullptr, nullptr, a), sc = solve_random_walk(p, nullptr, nullptr, c);
  CHECK((sa.var == sc.var).all());
  CHECK((sa.B == sc.B).all());
  const MatrixKernel kernel(p, survival_probabilities(p.rho, {}));
  const double z_crit = z_critical(sidak(1e-3, 18));
  int failed = 0;
  for (std::size_t i = 0; i < 6; ++i) {
    const auto x = test::gather_scores(WalkMethod::gather_absorption, kernel, i, 50000, 9);
    for (int ch = 0; ch < 3; ++ch) {
      const double b = B(static_cast<Eigen::Index>(i), ch);
      failed += !variance_matches(x[ch], va(static_cast<Eigen::Index>(i), ch), b * b, z_crit,
                                  "emitters patch " + std::to_string(i));
    }
  }
  CHECK(failed == 0);
}

TEST_CASE("finite-variance check reports radius >= 1 for a bad survival choice", "[walk][variance]") {
  const RadiosityProblem p = test::cube_problem(PatchRgb::Constant(6, 3, 0.9), PatchRgb::Constant(6, 3, 1.0));
  WalkOptions good, bad;
  bad.survival = {SurvivalRule::constant, 0.1};
  // K = (rho^2 / p) F with rows of F summing to 1: radius = rho^2 / p.
  CHECK(check_finite_variance(p, good).radius == Approx(0.9).epsilon(1e-5));
  CHECK(check_finite_variance(p, good).finite());
  const VarianceCheck b = check_finite_variance(p, bad);
  CHECK(b.radius == Approx(8.1).epsilon(1e-5));
  CHECK_FALSE(b.finite());
  bad.walks_per_patch = 100;
  const Solution s = solve_random_walk(p, nullptr, nullptr, bad);
  CHECK(s.info.at("variance_radius") >= 1);
  CHECK(s.message.find("infinite") != std::string::npos);
  CHECK(std::isinf(theoretical_variance(p, bad, dense_radiosity(p))(0, 0)));
}
