#include "solve/solve_radiosity.h"

#include "core/distributed.h"
#include "core/error.h"

namespace radwalk {

Solution solve_radiosity(const RadiosityProblem& p, const SolveOptions& options) {
  check_options(options);
  const std::string& name = options.solver;
  // Over MPI the LU is not distributed: every rank would factorise the whole system (core/distributed.h). Above
  // the size where it costs about a second it is refused.
  if (name == "direct" && distributed::size() > 1 && long(p.size()) > kAutoDirectMaxPatches)
    throw InputError("--solver direct: " + std::to_string(p.size()) + " patches > " +
                     std::to_string(kAutoDirectMaxPatches) +
                     ": the direct solve is not distributed over MPI ranks (each would factorise the whole system); "
                     "use --solver gauss-seidel or jacobi, whose sweeps are split over the ranks, or run one process");
  // Jacobi and Gauss-Seidel sweep a row-distributed F's own rows (distributed_sweeps.h); the direct solve
  // (a factorisation of the whole system) and Southwell (columns of F: its transpose) need the whole F, which
  // they gather (whole_problem: gather_whole_rows; docs/scaling.md, "Over MPI").
  const auto whole = [&p](auto&& solver, const SolveOptions& o) {
    return holds_own_rows_only(p.row_blocks) ? solver(whole_problem(p), o) : solver(p, o);
  };
  const auto direct = [](const RadiosityProblem& q, const SolveOptions& o) { return solve_direct(q, o); };
  const auto southwell = [](const RadiosityProblem& q, const SolveOptions& o) { return solve_southwell(q, o); };
  if (name == "direct") return whole(direct, options);
  if (name == "jacobi") return solve_jacobi(p, options);
  if (name == "gauss-seidel") return solve_gauss_seidel(p, options);
  if (name == "southwell") return whole(southwell, options);
  const auto gmres = [](const RadiosityProblem& q, const SolveOptions& o) { return solve_gmres(q, o); };
  if (name == "gmres") return whole(gmres, options);
  if (name != "auto")
    throw InputError("unknown solver '" + name + "' (expected auto, direct, jacobi, gauss-seidel, southwell or gmres)");

  const long n = long(p.size());
  const long direct_max = options.auto_direct_max_patches;
  const bool use_direct = n <= direct_max;
  const bool krylov = options.auto_iterative == "gmres";
  if (!krylov && options.auto_iterative != "gauss-seidel")
    throw InputError("auto_iterative must be gauss-seidel or gmres (got '" + options.auto_iterative + "')");
  Solution s = use_direct ? whole(direct, options) : krylov ? whole(gmres, options) : solve_gauss_seidel(p, options);
  const std::string why = use_direct ? "auto chose direct: " + std::to_string(n) + " patches <= " +
                                       std::to_string(direct_max) + ", where the exact LU solve costs under about a second. "
                                 : "auto chose " + options.auto_iterative + ": " + std::to_string(n) + " patches > " +
                                       std::to_string(direct_max) +
                                       ", where LU grows as N^3 in time and N^2 in memory. ";
  s.message = why + s.message;
  s.info["auto"] = 1;
  return s;
}

}  // namespace radwalk
