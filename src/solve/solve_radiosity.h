#pragma once
// The dispatcher behind `radwalk solve`: one entry point for the deterministic solvers.
//   "direct"        direct_solver.h   (dense or sparse LU, condition estimate)
//   "jacobi"        jacobi.h
//   "gauss-seidel"  gauss_seidel.h
//   "southwell"     southwell.h
//   "gmres"         gmres.h           (restarted GMRES, Gauss-Seidel preconditioned)
//   "auto"          the direct solve where it fits (N <= SolveOptions::auto_direct_max_patches, by default
//                   kAutoDirectMaxPatches), SolveOptions::auto_iterative otherwise; the
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

// Throws InputError for an unknown solver name, bad options or a bad problem.
Solution solve_radiosity(const RadiosityProblem& p, const SolveOptions& options = {});

}  // namespace radwalk
