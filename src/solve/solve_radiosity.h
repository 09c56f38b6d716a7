#pragma once
// The dispatcher behind `radwalk solve`: one entry point for the deterministic solvers.
//   "direct"        direct_solver.h   (dense or sparse LU, condition estimate)
//   "jacobi"        jacobi.h
//   "gauss-seidel"  gauss_seidel.h
//   "southwell"     southwell.h
//   "gmres"         gmres.h           (restarted GMRES, Gauss-Seidel preconditioned)
//   "auto"          the direct solve where it fits (N <= kAutoDirectMaxPatches), Gauss-Seidel otherwise; the
//                   Solution's message starts with the choice and the reason.
#include "solve/direct_solver.h"
#include "solve/gauss_seidel.h"
#include "solve/gmres.h"
#include "solve/jacobi.h"
#include "solve/problem.h"
#include "core/solution.h"
#include "solve/solve_options.h"
#include "solve/southwell.h"

namespace radwalk {

// Largest N for which "auto" picks the direct solver (measured: dense LU stays under about a second up to there; see solve_radiosity.cpp).
extern const long kAutoDirectMaxPatches;

// Throws InputError for an unknown solver name, bad options or a bad problem.
Solution solve_radiosity(const RadiosityProblem& p, const SolveOptions& options = {});

}  // namespace radwalk
