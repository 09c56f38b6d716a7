// Analytic references (docs/reference-data.md): furnace, unit cube with closed-form F, open parallel plates, energy
// balance of open scenes, Cohen's ambient term in the furnace, spectral radius against eigenvalues.
// Tolerances: a solver stopped at relative residual tol has relative error <= kappa_inf * tol; closed forms are
// evaluated with the float-rounded form factors the solvers see, plus kappa * 16 double epsilons of rounding.
#include <catch2/catch.hpp>
#include <Eigen/Eigenvalues>
#include <limits>

#include "core/error.h"
#include "scenes.h"
#include "solve/residual.h"
#include "solve/solve_radiosity.h"
#include "solve/spectral_radius.h"
#include "solve/synthetic_problem.h"

using namespace radwalk;
using namespace radwalk::test;

namespace {

const double kEps = std::numeric_limits<double>::epsilon();
const std::vector<std::string> kSolvers = {"direct", "jacobi", "gauss-seidel", "southwell"};

Solution run(const std::string& solver, const RadiosityProblem& p, double tol) {
  SolveOptions o;
  o.solver = solver;
  o.tol = tol;
  o.max_iterations = 1'000'000;
  return solve_radiosity(p, o);
}

double stored(double f) { return double(float(f)); }

// kappa_inf of I - rho F for a closed cube with uniform rho: (1 + rho s) / (1 - rho s), s the row sum.
double cube_condition(double rho) {
  const double s = stored(kOpposite) + 4 * stored(kAdjacent);
  return (1 + rho * s) / (1 - rho * s);
}

}  // namespace

TEST_CASE("furnace: B = E / (1 - rho) on every face", "[solve][analytic]") {
  const double E = 2.5, tol = 1e-12;
  const double row_sum = stored(kOpposite) + 4 * stored(kAdjacent);  // 1 up to float rounding of F
  for (double rho : {0.1, 0.5, 0.9, 0.99}) {
    const RadiosityProblem p = furnace(rho, E);
    const double kappa = cube_condition(rho);
    for (const auto& solver : kSolvers) {
      const Solution s = run(solver, p, tol);
      INFO(solver << ", rho " << rho << ": " << s.message);
      REQUIRE(s.status == SolveStatus::converged);
      // Exact for the stored F (its rows sum to row_sum), and E / (1 - rho) to the precision of float F.
      const double exact_stored = E / (1 - rho * row_sum), exact = E / (1 - rho);
      CHECK((s.B - exact_stored).abs().maxCoeff() <= kappa * (tol + 16 * kEps) * exact_stored);
      CHECK((s.B - exact).abs().maxCoeff() <= kappa * (tol + 16 * kEps + rho * std::abs(1 - row_sum)) * exact);
    }
  }
}

TEST_CASE("unit cube with a lit ceiling matches its closed-form solution", "[solve][analytic]") {
  // By symmetry: ceiling c, floor f, four walls w. With Fo (opposite), Fa (adjacent):
  //   c = Ec + rho (Fo f + 4 Fa w),  f = rho (Fo c + 4 Fa w),  w = rho (Fa c + Fa f + (2 Fa + Fo) w).
  // Then d = c - f = Ec / (1 + rho Fo), w = rho Fa s / (1 - rho (2 Fa + Fo)) with s = c + f, and
  //   s = Ec / [1 - rho Fo - 8 rho^2 Fa^2 / (1 - rho (2 Fa + Fo))].
  const Rgb rho(0.3, 0.6, 0.95), Ec(10, 20, 30);
  const double Fo = stored(kOpposite), Fa = stored(kAdjacent), tol = 1e-12;
  const RadiosityProblem p = lit_cube(rho, Ec);
  PatchRgb exact(6, 3);
  for (int ch = 0; ch < 3; ++ch) {
    const double r = rho(ch), e = Ec(ch);
    const double wall_gain = 1 - r * (2 * Fa + Fo);
    const double s = e / (1 - r * Fo - 8 * r * r * Fa * Fa / wall_gain);
    const double d = e / (1 + r * Fo);
    const double w = r * Fa * s / wall_gain;
    exact.col(ch) << (s - d) / 2, (s + d) / 2, w, w, w, w;
  }
  const double kappa = cube_condition(rho.maxCoeff());
  for (const auto& solver : kSolvers) {
    const Solution s = run(solver, p, tol);
    INFO(solver << ": " << s.message);
    REQUIRE(s.status == SolveStatus::converged);
    for (int ch = 0; ch < 3; ++ch)
      CHECK((s.B.col(ch) - exact.col(ch)).abs().maxCoeff() <=
            kappa * (tol + 16 * kEps) * exact.col(ch).abs().maxCoeff());
  }
}

TEST_CASE("open parallel plates: B1 = (E1 + rho1 F E2) / (1 - rho1 rho2 F^2), energy balanced",
          "[solve][analytic]") {
  const Rgb rho1(0.5, 0.9, 0.0), rho2(0.7, 0.2, 0.3), E1(4, 0, 1), E2(1, 3, 0);
  const RadiosityProblem p = plates(rho1, rho2, E1, E2);
  const double F = stored(kOpposite), tol = 1e-12;
  const Rgb B1 = (E1 + rho1 * F * E2) / (1 - rho1 * rho2 * F * F);
  const Rgb B2 = (E2 + rho2 * F * E1) / (1 - rho1 * rho2 * F * F);
  const double kappa = (1 + 0.9 * F) / (1 - 0.9 * F);  // >= kappa_inf of either 2 x 2 system
  for (const auto& solver : kSolvers) {
    const Solution s = run(solver, p, tol);
    INFO(solver << ": " << s.message);
    REQUIRE(s.status == SolveStatus::converged);
    for (int c = 0; c < 3; ++c) {
      const double scale = std::max(B1(c), B2(c));
      CHECK(std::abs(s.B(0, c) - B1(c)) <= kappa * (tol + 16 * kEps) * scale);
      CHECK(std::abs(s.B(1, c) - B2(c)) <= kappa * (tol + 16 * kEps) * scale);
    }
  }
}

TEST_CASE("energy balance in open scenes: emitted = absorbed + escaped", "[solve][analytic]") {
  // Power leaving patch i is A_i B_i; what arrives is A_i (F B)_i by reciprocity (A_i F_ij = A_j F_ji), of which
  // A_i (1 - rho_i) (F B)_i is absorbed; A_i B_i (1 - sum_j F_ij) escapes. Summing B = E + rho F B over A_i:
  //   sum A_i E_i = sum A_i (1 - rho_i) (F B)_i + sum A_i B_i (1 - sum_j F_ij),
  // exactly for the solution; an approximate B misses it by |sum A_i r_i| <= A_total ||r||_inf.
  // (The absorbed term is (1 - rho_i) times the irradiance F B, not times B: they agree only in a furnace.)
  RadiosityProblem box = lit_cube(Rgb(0.4, 0.7, 0.9), Rgb(3, 2, 1));  // the cube without its floor
  {
    RadiosityProblem open;
    const std::vector<int> keep = {1, 2, 3, 4, 5};
    const Eigen::MatrixXd F = Eigen::MatrixXd(box.F.cast<double>());
    Eigen::MatrixXd Fo(5, 5);
    for (int a = 0; a < 5; ++a)
      for (int b = 0; b < 5; ++b) Fo(a, b) = F(keep[a], keep[b]);
    open.F = Fo.cast<float>().sparseView();
    open.rho = box.rho.topRows(5);
    open.E = box.E.bottomRows(5);
    open.area = Eigen::VectorXd::Ones(5);
    box = open;
  }
  const std::vector<std::pair<std::string, RadiosityProblem>> scenes = {
      {"plates", plates(Rgb(0.5, 0.9, 0.1), Rgb(0.7, 0.2, 0.3), Rgb(4, 0, 1), Rgb(1, 3, 0))},
      {"open box", box}};
  const double tol = 1e-10;
  for (const auto& [name, p] : scenes) {
    const Eigen::VectorXd row_sum = Eigen::MatrixXd(p.F.cast<double>()).rowwise().sum();
    REQUIRE(row_sum.maxCoeff() < 0.9);  // open: some power escapes
    for (const auto& solver : kSolvers) {
      const Solution s = run(solver, p, tol);
      INFO(name << ", " << solver << ": " << s.message);
      REQUIRE(s.status == SolveStatus::converged);
      const PatchRgb FB = multiply_F(p.F, s.B);
      const Rgb scale = residual_scale(p.E);
      for (int c = 0; c < 3; ++c) {
        double emitted = 0, absorbed = 0, escaped = 0;
        for (Eigen::Index i = 0; i < Eigen::Index(p.size()); ++i) {
          emitted += p.area(i) * p.E(i, c);
          absorbed += p.area(i) * (1 - p.rho(i, c)) * FB(i, c);
          escaped += p.area(i) * s.B(i, c) * (1 - row_sum(i));
        }
        CHECK(std::abs(emitted - absorbed - escaped) <=
              p.area.sum() * (s.residual * scale(c) + 16 * kEps * s.B.col(c).maxCoeff()));
      }
    }
  }
}

TEST_CASE("Cohen's ambient term completes any uniform guess in the furnace", "[solve][southwell]") {
  // Furnace, B = alpha E: the unshot dB = E - (I - H) B is uniform, and B + dB + rho R mean(dB) with
  // R = 1 / (1 - rho) is E / (1 - rho) up to the float rounding of the row sums.
  const double rho = 0.8, E = 1.5;
  const RadiosityProblem p = furnace(rho, E);
  const double row_sum = stored(kOpposite) + 4 * stored(kAdjacent);
  for (double alpha : {0.0, 0.5, 1.0, 3.0}) {
    const PatchRgb B = PatchRgb::Constant(6, 3, alpha * E);
    const PatchRgb display = B + residual(p, B) + southwell_ambient(p, B);
    CHECK((display - E / (1 - rho)).abs().maxCoeff() <=
          cube_condition(rho) * (rho * std::abs(1 - row_sum) + 16 * kEps) * E / (1 - rho));
  }
  const Solution s = solve_southwell(p, {});
  CHECK(s.info.count("ambient_r") == 1);
  CHECK(std::abs(s.info.at("ambient_r")) <= s.residual * E / (1 - rho));  // nothing left to add once converged
  // rho = 1 everywhere: the interreflection factor 1 / (1 - rho_avg) does not exist, a numerical refusal.
  CHECK_THROWS_AS(southwell_ambient(furnace(1.0, E), PatchRgb::Constant(6, 3, E)), NumericalError);
}

TEST_CASE("spectral radius bounds bracket the largest eigenvalue of diag(rho) F", "[solve][stability]") {
  for (const RadiosityProblem& p : {sphere(30, 5), make_synthetic_problem(300, 32, 9)}) {
    double true_radius = 0;
    for (int c = 0; c < 3; ++c) {
      const Eigen::MatrixXd H = p.rho.col(c).matrix().asDiagonal() * Eigen::MatrixXd(p.F.cast<double>());
      true_radius = std::max(true_radius, Eigen::EigenSolver<Eigen::MatrixXd>(H, false).eigenvalues().cwiseAbs().maxCoeff());
    }
    const SpectralRadius bound = spectral_radius_bound(p);
    const SpectralRadius r = estimate_spectral_radius(p);
    INFO("true " << true_radius << ", bound " << bound.bound << ", [" << r.lower << ", " << r.upper << "], est "
                 << r.estimate << " after " << r.products << " products");
    CHECK(bound.bound >= true_radius * (1 - 1e-12));
    CHECK(r.lower <= true_radius * (1 + 1e-12));
    CHECK(r.upper >= true_radius * (1 - 1e-12));
    CHECK(r.products > 0);
    CHECK(std::abs(r.estimate - true_radius) <= 1e-4 * true_radius);  // the requested bracket width
  }
}
