#pragma once
// Options shared by the deterministic solvers and the dispatcher solve_radiosity().
#include <string>

namespace radwalk {

struct SolveOptions {
  std::string solver = "auto";  // "auto" | "direct" | "jacobi" | "gauss-seidel" | "southwell"
  double tol = 1e-10;           // stop when max_c ||E_c - (I - H_c) B_c||_inf / ||E_c||_inf <= tol (> 0)
  long max_iterations = 10000;  // sweeps (Jacobi, Gauss-Seidel) or shots (Southwell), >= 0
  bool record_history = true;   // fill Solution.residual_history (one entry per sweep, or per N shots)
};

// Throws InputError unless tol > 0 (finite) and max_iterations >= 0.
void check_options(const SolveOptions& options);

}  // namespace radwalk
