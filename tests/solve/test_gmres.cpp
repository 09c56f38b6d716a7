// The restarted GMRES solver (solve/gmres.h): against the dense LU on the net-radiation cube and on a closed,
// nearly singular enclosure of re-radiating rows (rho = 1) where Gauss-Seidel cannot converge within the same
// budget; the stopping test is the exact residual of the system.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "solve/block_gmres.h"
#include "solve/net_radiation.h"
#include "solve/residual.h"
#include "solve/solve_radiosity.h"
#include "solve/synthetic_problem.h"
#include "support/reference_problems.h"

using namespace radwalk;

namespace {

// The unit cube, faces of emissivity 0.3 .. 0.9 at 300 .. 500 K, faces 3 and 4 re-radiating (q = 0 and q = -150
// W/m^2: a negative source, so both channels of the split are solved).
NetRadiationInput cube_input() {
  NetRadiationInput in;
  in.area.assign(6, 1.0);
  for (int i = 0; i < 6; ++i) {
    SurfaceCondition s;
    s.emissivity = 0.3 + 0.12 * i;
    s.temperature = 300 + 40 * i;
    in.surface.push_back(s);
  }
  in.surface[3].temperature_given = false;
  in.surface[3].heat_flux = 0;
  in.surface[4].temperature_given = false;
  in.surface[4].heat_flux = -150;
  return in;
}

// A closed enclosure of n patches with the row structure of traced form factors (synthetic_problem.h) whose rows
// are scaled to sum to 1, every patch re-radiating (rho = 1, source q_i in [0, 50) W/m^2) but `black` black
// patches (rho = 0, source sigma 300^4): radiation is absorbed only there, so the spectral radius of diag(rho) F
// is close to 1.
RadiosityProblem nearly_singular(long n, int black) {
  RadiosityProblem p = make_synthetic_problem(n, 200, 7);
  for (Eigen::Index i = 0; i < p.F.rows(); ++i) {
    double sum = 0;
    for (SparseF::InnerIterator it(p.F, i); it; ++it) sum += it.value();
    for (SparseF::InnerIterator it(p.F, i); it; ++it) it.valueRef() = float(it.value() / sum);
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    const bool is_black = i % (n / black) == 0;
    p.rho.row(i).setConstant(is_black ? 0.0 : 1.0);
    p.E.row(i).setConstant(is_black ? kStefanBoltzmann * std::pow(300.0, 4) : double((i * 37) % 50));
  }
  return p;
}

}  // namespace

TEST_CASE("gmres: the net-radiation cube with two re-radiating faces matches the dense LU of the radiosity form "
          "to 1e-9",
          "[solve][gmres]") {
  const NetRadiationInput in = cube_input();
  const SparseF F = test::unit_cube_F();
  const std::vector<double> reference = dense_net_radiation(in, F);
  SolveOptions o;
  o.solver = "gmres";
  o.tol = 1e-13;
  const Solution s = solve_radiosity(net_radiation_problem(in, F), o);
  REQUIRE(s.status == SolveStatus::converged);
  CHECK(s.residual <= 1e-13);
  const std::vector<double> J = radiosity_of(s);
  for (std::size_t i = 0; i < 6; ++i) {
    INFO("face " << i << ": J = " << J[i] << ", dense LU " << reference[i]);
    CHECK(std::abs(J[i] - reference[i]) <= 1e-9 * std::abs(reference[i]));
  }
  // Channel 2 is a copy of channel 0 (net_radiation.h): solved once.
  CHECK(s.info.at("channels_solved") == 2);
  CHECK((s.B.col(2) == s.B.col(0)).all());
}

TEST_CASE("gmres: a closed enclosure of re-radiating rows (radius of diag(rho) F near 1) converges to the dense "
          "LU's solution where Gauss-Seidel runs out of the same budget",
          "[solve][gmres]") {
  const RadiosityProblem p = nearly_singular(1000, 4);
  SolveOptions o;
  o.tol = 1e-10;
  o.max_iterations = 400;
  o.solver = "direct";
  const Solution direct = solve_radiosity(p, o);
  REQUIRE(direct.status == SolveStatus::converged);
  o.solver = "gmres";
  const Solution g = solve_radiosity(p, o);
  INFO(g.message);
  REQUIRE(g.status == SolveStatus::converged);
  CHECK(g.iterations <= 400);
  CHECK(relative_residual(p, g.B) <= 1e-10);
  // The residual bounds the error through kappa; with the direct solve's own rounding the two agree to 1e-7.
  const double scale = direct.B.col(0).matrix().lpNorm<Eigen::Infinity>();
  CHECK((g.B.col(0) - direct.B.col(0)).matrix().lpNorm<Eigen::Infinity>() <= 1e-7 * scale);
  o.solver = "gauss-seidel";
  const Solution gs = solve_radiosity(p, o);
  INFO("gauss-seidel: " << gs.message);
  CHECK(gs.status != SolveStatus::converged);
}

TEST_CASE("gmres: a singular system (every row re-radiating, rows of F summing to 1 up to the float rounding) "
          "is reported as diverged, never as converged",
          "[solve][gmres]") {
  NetRadiationInput in = cube_input();
  const SparseF F = test::unit_cube_F();
  RadiosityProblem p = net_radiation_problem(in, F);
  p.rho.setOnes();  // every face re-radiating: I - F is singular (its null space the constants)
  p.E.setZero();
  p.E(0, 0) = 100;  // a net source that cannot be balanced
  SolveOptions o;
  o.solver = "gmres";
  o.tol = 1e-12;
  o.max_iterations = 500;
  const Solution s = solve_radiosity(p, o);
  INFO(s.message << " B(:,0) = " << s.B.col(0).transpose());
  CHECK(s.status == SolveStatus::diverged);
}

TEST_CASE("block gmres: agrees with block Jacobi where both converge and solves the nearly singular enclosure where "
          "block Jacobi cannot",
          "[solve][gmres]") {
  // Two probes (six columns) of deterministic right-hand sides.
  const auto rhs = [](Eigen::Index n) {
    RowBlock Z(n, 6);
    for (Eigen::Index i = 0; i < n; ++i)
      for (Eigen::Index k = 0; k < 6; ++k) Z(i, k) = double((i * 7 + k * 13) % 11) - 5.0;
    return Z;
  };
  SECTION("rho 0.9: block Jacobi converges") {
    RadiosityProblem p = make_synthetic_problem(500, 100, 3);
    p.rho.setConstant(0.9);
    const RowBlock Z = rhs(500);
    const BlockSolution jacobi = solve_block_jacobi(p, Z, 1e-12, "test");
    const BlockSolution krylov = solve_block_gmres(p, Z, 1e-12, "test");
    CHECK(krylov.sweeps < jacobi.sweeps);
    CHECK((krylov.X - jacobi.X).abs().maxCoeff() <= 1e-9 * jacobi.X.abs().maxCoeff());
  }
  SECTION("closed enclosure of re-radiating rows: block GMRES matches GMRES per column, block Jacobi's stop on a "
          "small change (1e-6) is far from it") {
    const RadiosityProblem p = nearly_singular(1000, 4);
    RowBlock Z = rhs(1000).abs();  // non-negative: a radiosity source
    const BlockSolution jacobi = solve_block_jacobi(p, Z, 1e-6, "test");
    const BlockSolution krylov = solve_block_gmres(p, Z, 1e-10, "test");
    for (Eigen::Index k = 0; k < 6; k += 3) {
      RadiosityProblem q = p;
      q.E = PatchRgb(1000, 3);
      for (int c = 0; c < 3; ++c) q.E.col(c) = Z.col(k + c);
      SolveOptions o;
      o.solver = "gmres";
      o.tol = 1e-12;
      const Solution s = solve_radiosity(q, o);
      REQUIRE(s.status == SolveStatus::converged);
      for (int c = 0; c < 3; ++c) {
        const double scale = s.B.col(c).abs().maxCoeff();
        CHECK((krylov.X.col(k + c) - s.B.col(c)).abs().maxCoeff() <= 1e-7 * scale);
        const double jacobi_error = (jacobi.X.col(k + c) - s.B.col(c)).abs().maxCoeff() / scale;
        INFO("block Jacobi: " << jacobi.sweeps << " sweeps, relative error " << jacobi_error);
        CHECK(jacobi_error > 1e-4);
      }
    }
  }
}
