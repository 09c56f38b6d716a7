// SolveOptions::on_iterate: the iterative solvers report every sweep (or every iterate_every shots) with the
// current iterate, and the last report is the returned solution.
#include <catch2/catch.hpp>
#include <vector>

#include "core/error.h"
#include "solve/solve_radiosity.h"
#include "solve/synthetic_problem.h"

using namespace radwalk;

namespace {

struct Calls {
  std::vector<long> iterations;
  PatchRgb last;
};

Solution solve_recording(const RadiosityProblem& p, SolveOptions o, Calls& calls) {
  o.on_iterate = [&](long k, const PatchRgb& B) {
    calls.iterations.push_back(k);
    calls.last = B;
  };
  return solve_radiosity(p, o);
}

}  // namespace

TEST_CASE("on_iterate: once per sweep for Jacobi and Gauss-Seidel, last iterate = returned B", "[solve]") {
  const RadiosityProblem p = make_synthetic_problem(300, 64, 5);
  for (const char* solver : {"jacobi", "gauss-seidel"}) {
    INFO(solver);
    SolveOptions o;
    o.solver = solver;
    Calls calls;
    const Solution s = solve_recording(p, o, calls);
    REQUIRE(s.status == SolveStatus::converged);
    REQUIRE(long(calls.iterations.size()) == s.iterations);
    for (std::size_t k = 0; k < calls.iterations.size(); ++k) CHECK(calls.iterations[k] == long(k + 1));
    CHECK((calls.last == s.B).all());
  }
}

TEST_CASE("on_iterate: Southwell every iterate_every shots, plus the last shot", "[solve]") {
  const RadiosityProblem p = make_synthetic_problem(200, 64, 6);
  SolveOptions o;
  o.solver = "southwell";
  o.iterate_every = 7;
  o.max_iterations = 1000 * 200;
  Calls calls;
  const Solution s = solve_recording(p, o, calls);
  REQUIRE(s.status == SolveStatus::converged);
  REQUIRE(!calls.iterations.empty());
  for (std::size_t k = 0; k + 1 < calls.iterations.size(); ++k) CHECK(calls.iterations[k] == 7 * long(k + 1));
  CHECK(calls.iterations.back() == s.iterations);
  CHECK((calls.last == s.B).all());

  o.iterate_every = -1;
  CHECK_THROWS_AS(solve_recording(p, o, calls), InputError);
}

TEST_CASE("on_iterate: unset costs nothing and changes nothing, the direct solver never calls it", "[solve]") {
  const RadiosityProblem p = make_synthetic_problem(100, 64, 7);
  SolveOptions o;
  o.solver = "gauss-seidel";
  const Solution plain = solve_radiosity(p, o);
  Calls calls;
  const Solution recorded = solve_recording(p, o, calls);
  CHECK((plain.B == recorded.B).all());
  o.solver = "direct";
  Calls none;
  solve_recording(p, o, none);
  CHECK(none.iterations.empty());
}
