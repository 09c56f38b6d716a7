#pragma once
// What every solver returns (deterministic, random walk, path tracer): radiosity per patch and channel, how it
// was obtained, and how good it is.
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "core/types.h"

namespace radwalk {

enum class SolveStatus {
  converged,       // met its tolerance (deterministic) or finished its walks (Monte Carlo)
  max_iterations,  // stopped at the iteration budget before the tolerance
  diverged,        // the iteration grew or cannot converge (spectral radius >= 1)
  refused,         // the system was refused before solving (singular, invalid input)
};
const char* to_string(SolveStatus status);

struct Solution {
  std::string method;       // "direct", "jacobi", "gauss-seidel", "southwell", "gather-absorption", ...
  SolveStatus status = SolveStatus::converged;
  std::string message;      // why it stopped, in words, and what to do if it failed
  PatchRgb B;               // radiosity B = E + rho * (F B), W/m^2, one row per patch
  PatchRgb B_se;            // statistical standard error of B (Monte Carlo methods; deterministic solvers from traced
                            // form factors: their noise, apps/statistical_error.h); empty when unknown
  PatchRgb B_disc;          // estimated discretisation error of B (solve/discretisation_error.h: 1 standard deviation
                            // equivalent); empty when not estimated
  PatchRgb var;             // per-walk (per-sample) variance (Monte Carlo methods); empty otherwise
  PatchRgb var_theory;      // exact per-walk variance where computable; empty otherwise
  PatchRgb vov;             // variance of the variance (core/moments.h CentralMoments4::vov: how far B_se can be
                            // trusted, reliable below kVovReliable): the path tracer's; empty otherwise
  long iterations = 0;      // sweeps or shots (deterministic)
  double residual = std::numeric_limits<double>::quiet_NaN();  // ||B - E - rho F B|| / ||E||, max over channels
  std::vector<double> residual_history;
  long walks = 0;           // walks or particles (Monte Carlo)
  long steps = 0;           // transitions taken (Monte Carlo)
  double seconds = 0;       // wall time of the solve alone
  std::map<std::string, double> info;  // solver-specific numbers (condition estimate, spectral radius, ...)
};

}  // namespace radwalk
