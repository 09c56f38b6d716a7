#pragma once
// When the iterative solvers (Jacobi, Gauss-Seidel, Southwell) can, cannot, or did not converge.
//
// Before iterating, check_stability() bounds the spectral radius of H_c = diag(rho_c) F (spectral_radius.h):
//  - radius >= 1 (within kRadiusOneTolerance, the precision of the float F): the Neumann series diverges ->
//    status diverged, nothing is iterated;
//  - the iterations needed, about rate_factor * log(tol) / log(radius), exceed max_iterations -> status
//    max_iterations, nothing is iterated. rate_factor is the solver's optimistic rate per sweep relative to
//    Jacobi (Gauss-Seidel on a consistently ordered matrix converges twice as fast: 0.5), so a refusal is sure.
// While iterating, judge_progress() reads the relative residual history (one entry per sweep):
//  converged (<= tol); diverged (not finite, grown kGrowthFactor above its minimum, or growing over the last
//  kRateWindow entries and 10 times above its minimum); too slow (at the rate
//  observed over the last kRateWindow entries the budget cannot reach tol; early rates are faster than the
//  asymptotic one, so the projection is optimistic); stagnated (no decrease over kRateWindow entries: tol is
//  below the rounding level); out of budget.
#include <string>
#include <vector>

#include "solve/problem.h"
#include "solve/residual.h"
#include "core/solution.h"
#include "solve/solve_options.h"
#include "solve/iteration_progress.h"
#include "solve/spectral_radius.h"

namespace radwalk {

// A radius within this of 1 is 1: F is stored in float, so its row sums carry relative rounding of ~1e-7.
inline constexpr double kRadiusOneTolerance = 1e-6;
inline constexpr double kGrowthFactor = 1e3;
inline constexpr int kRateWindow = 10;

struct StabilityCheck {
  bool ok = true;                                   // iterate
  SolveStatus status = SolveStatus::converged;      // diverged or max_iterations when !ok
  std::string message;                              // why not, and what to do
  SpectralRadius radius;                            // bound, or power-iteration estimate when it was needed
  double iterations_needed = 0;                     // rate_factor * log(tol) / log(radius); inf if radius >= 1
};

// method names the solver in messages ("jacobi").
StabilityCheck check_stability(const RadiosityProblem& p, const SolveOptions& options, const std::string& method,
                               double rate_factor);

// How an iteration is going, as judged from its residual history.
enum class Verdict { keep_going, converged, diverged, too_slow, stagnated };

// history[k]: relative residual after k entries of entry_size iterations each. Fills *why when it stops.
Verdict judge_progress(const std::vector<double>& history, long entry_size, const SolveOptions& options,
                       const std::string& method, std::string* why);

// The verdict a failed check stands for: diverged, or too_slow (status max_iterations); keep_going if ok.
Verdict refusal(const StabilityCheck& check);

// Puts radius and needed iterations into Solution.info ("spectral_radius_bound", "spectral_radius_estimate",
// "spectral_radius_lower", "iterations_needed").
void record_stability(const StabilityCheck& check, Solution& s);

// Ends an iterative solve: sets s.B (a non-finite iterate is replaced by E and said so), the exact relative
// residual of B, status (converged whenever that residual is <= tol), message, iterations and history.
void finish_iterative(Solution& s, const RadiosityProblem& p, const SolveOptions& options, PatchRgb B,
                      Verdict verdict, const std::string& why, long iterations, std::vector<double> history,
                      const std::string& unit);

// The sweep loop of Jacobi and Gauss-Seidel, from the iterate B: each call sweep(B) updates B in place by one
// sweep and returns the relative residual of the iterate it started from (max_ic |r_ic| / scale_c; not finite
// when the iteration broke down). After each sweep: progress ("METHOD sweeps", core/progress.h), on_iterate, then
// judge_progress on the history; a converged verdict is confirmed on the new iterate (the residual was the
// previous one's). Ends with finish_iterative.
template <class Sweep>
void run_sweeps(Solution& s, const RadiosityProblem& p, const SolveOptions& options, PatchRgb B, Sweep&& sweep) {
  std::vector<double> history;
  std::string why;
  Verdict verdict = Verdict::keep_going;
  long sweeps = 0;
  IterationProgress progress(s.method + " sweeps", options.tol, options.max_iterations);
  while (sweeps < options.max_iterations) {
    history.push_back(sweep(B));
    ++sweeps;
    progress.update(sweeps, history.back());
    if (options.on_iterate) options.on_iterate(sweeps, B);
    verdict = judge_progress(history, 1, options, s.method, &why);
    if (verdict == Verdict::converged) {
      if (relative_residual(p, B) <= options.tol) break;
      verdict = Verdict::keep_going;  // rounding: r(B^k) met tol but B^{k+1} did not yet
    } else if (verdict != Verdict::keep_going) {
      break;
    }
  }
  progress.finish();
  finish_iterative(s, p, options, std::move(B), verdict, why, sweeps, std::move(history), "sweeps");
}

}  // namespace radwalk
