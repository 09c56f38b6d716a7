#pragma once
// Options shared by the deterministic solvers and the dispatcher solve_radiosity().
#include <cstddef>
#include <functional>
#include <string>

#include "core/types.h"

namespace radwalk {

// Largest N for which "auto" picks the direct solver by default (measured with bench_solvers, synthetic F with 1000
// rays per patch, tol 1e-10, 2 shared cores: dense LU 0.13 s and 32 MB at 1000 patches, 0.90 s and 124 MB at 2000,
// 7.5 s and 489 MB at 4000; Gauss-Seidel 0.010, 0.025 and 0.18 s). The direct solve is exact, robust near radius 1
// and gives the condition number; it stays under about a second and 130 MB up to 2000 patches, and grows as N^3 in
// time and N^2 in memory beyond.
inline constexpr long kAutoDirectMaxPatches = 2000;

struct SolveOptions {
  std::string solver = "auto";  // "auto" | "direct" | "jacobi" | "gauss-seidel" | "southwell" | "gmres"
  // "auto": the direct solve up to this many patches (>= 0), auto_iterative above.
  long auto_direct_max_patches = kAutoDirectMaxPatches;
  // The iterative solver "auto" takes above auto_direct_max_patches: "gauss-seidel" (radiosity, rho < 1: its
  // sweeps converge at the rate of the spectral radius) or "gmres" (the net-radiation system, whose re-radiating
  // rows rho = 1 bring the radius close to 1; docs/theory/net_radiation.md, "The Krylov solver").
  std::string auto_iterative = "gauss-seidel";
  double tol = 1e-10;           // stop when max_c ||E_c - (I - H_c) B_c||_inf / ||E_c||_inf <= tol (> 0)
  long max_iterations = 10000;  // sweeps (Jacobi, Gauss-Seidel) or shots (Southwell), >= 0
  bool record_history = true;   // fill Solution.residual_history (one entry per sweep, or per N shots)
  // Progress of the iterative solvers (empty: never called, no cost). Jacobi and Gauss-Seidel call it after every
  // sweep k = 1, 2, ... with the iterate B^k; Southwell after every `iterate_every` shots (0: every N shots) with
  // the shot count, and once more after the last shot if that was not a multiple. The last call's B equals the
  // returned Solution::B. Not called by the direct solver or when the stability check refuses to iterate.
  std::function<void(long iteration, const PatchRgb& B)> on_iterate;
  long iterate_every = 0;       // Southwell: shots between on_iterate calls (0: N), >= 0
};

// The iteration budget when none is given (the CLI's --max-iterations 0): 1000 x N shots for "southwell", 10000
// sweeps for every other solver.
long default_max_iterations(const std::string& solver, std::size_t patches);

// Throws InputError unless tol > 0 (finite), max_iterations >= 0 and auto_direct_max_patches >= 0 (Southwell also
// refuses iterate_every < 0).
void check_options(const SolveOptions& options);

}  // namespace radwalk
