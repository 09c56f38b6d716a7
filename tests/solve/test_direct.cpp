// The direct solver: one factorisation when channels share rho, dense and sparse LU agree, reuse for new E.
#include <catch2/catch.hpp>

#include "scenes.h"
#include "solve/direct_solver.h"
#include "solve/residual.h"
#include "solve/synthetic_problem.h"

using namespace radwalk;
using namespace radwalk::test;

TEST_CASE("one factorisation when the channels share rho, one per distinct rho column", "[solve][direct]") {
  CHECK(solve_direct(furnace(0.5, 1)).info.at("factorisations") == 1);
  CHECK(solve_direct(lit_cube(Rgb(0.5, 0.5, 0.7), Rgb::Ones())).info.at("factorisations") == 2);
  CHECK(solve_direct(lit_cube(Rgb(0.3, 0.5, 0.7), Rgb::Ones())).info.at("factorisations") == 3);
}

TEST_CASE("a DirectSolver factorises once and solves new emissions", "[solve][direct]") {
  RadiosityProblem p = make_synthetic_problem(300, 32, 4);
  for (DirectMethod method : {DirectMethod::dense, DirectMethod::sparse}) {
    const DirectSolver solver(p, method);
    REQUIRE(solver.ok());
    CHECK(solver.dense() == (method == DirectMethod::dense));
    const double kappa = solver.condition_estimate();
    for (int trial = 0; trial < 2; ++trial) {
      p.E = PatchRgb::Zero(300, 3);
      p.E.row(17 + 100 * trial) = Rgb(1, 2, 3).transpose();
      const Solution s = solver.solve(p);
      REQUIRE(s.status == SolveStatus::converged);
      // A backward-stable LU leaves a residual of a modest multiple of N * epsilon.
      CHECK(s.residual <= 300 * std::numeric_limits<double>::epsilon() * kappa);
      CHECK(relative_difference(s.B, dense_reference(p)) <= 1e-9);
    }
  }
}

TEST_CASE("an empty problem solves to an empty B", "[solve][direct]") {
  RadiosityProblem p;
  p.F.resize(0, 0);
  p.rho.resize(0, 3);
  p.E.resize(0, 3);
  const Solution s = solve_direct(p);
  CHECK(s.status == SolveStatus::converged);
  CHECK(s.B.rows() == 0);
}
