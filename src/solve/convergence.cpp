#include "solve/convergence.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/format_number.h"
#include "solve/residual.h"

namespace radwalk {
namespace {

double needed(double tol, double radius, double rate_factor) {
  if (radius <= 0) return 1;
  if (radius >= 1) return std::numeric_limits<double>::infinity();
  return std::max(1.0, std::ceil(rate_factor * std::log(tol) / std::log(radius)));
}

}  // namespace

StabilityCheck check_stability(const RadiosityProblem& p, const SolveOptions& options, const std::string& method,
                               double rate_factor) {
  StabilityCheck check;
  check.radius = spectral_radius_bound(p);
  const double budget = double(options.max_iterations);
  check.iterations_needed = needed(options.tol, check.radius.bound, rate_factor);
  if (check.iterations_needed <= budget) return check;

  // The bound alone cannot clear it: estimate the radius and use its lower bound (the optimistic side).
  check.radius = estimate_spectral_radius(p);
  const SpectralRadius& r = check.radius;
  const double radius = r.lower > 0 ? r.lower : r.estimate;
  const std::string described = format_number(r.estimate) + " (bounds [" + format_number(r.lower) + ", " +
                                format_number(r.upper) + "], channel " + std::to_string(r.channel) + ")";
  if (r.lower >= 1 - kRadiusOneTolerance || r.estimate >= 1 - kRadiusOneTolerance) {
    check.ok = false;
    check.status = SolveStatus::diverged;
    check.iterations_needed = std::numeric_limits<double>::infinity();
    check.message =
        method + " cannot converge: the spectral radius of diag(rho) F is " + described +
        ", not below 1, so the series B = sum_k (diag(rho) F)^k E diverges and no finite non-negative"
        " radiosity exists (max rho = " +
        format_number(r.max_rho) + ", max row sum of F = " + format_number(r.max_row_sum) +
        ", at most 1 for valid form factors). Check the reflectances (each must"
        " be < 1 where the scene is closed) and the form factors (rows must sum to <= 1).";
    return check;
  }
  check.iterations_needed = needed(options.tol, radius, rate_factor);
  if (check.iterations_needed > budget) {
    check.ok = false;
    check.status = SolveStatus::max_iterations;
    check.message =
        method + " would not reach tol " + format_number(options.tol) + " within max-iterations " +
        std::to_string(options.max_iterations) + ": the spectral radius of diag(rho) F is " + described +
        ", so it needs about " + format_number(check.iterations_needed) +
        " iterations. Raise --max-iterations above that, use the direct solver, or loosen the tolerance.";
  }
  return check;
}

Verdict judge_progress(const std::vector<double>& h, long entry_size, const SolveOptions& options,
                       const std::string& method, std::string* why) {
  const double last = h.back();
  const long k = long(h.size()) - 1;
  const long done = k * entry_size;
  if (!std::isfinite(last)) {
    *why = method + " diverged: the relative residual is not finite after " + std::to_string(done) +
           " iterations. Use the direct solver and check reflectances and form factors.";
    return Verdict::diverged;
  }
  if (last <= options.tol) return Verdict::converged;
  const double least = *std::min_element(h.begin(), h.end());
  if (last > kGrowthFactor * least) {
    *why = method + " diverged: the relative residual grew from " + format_number(least) + " to " +
           format_number(last) + " in " + std::to_string(done) +
           " iterations, so the spectral radius of its iteration is >= 1. Use the direct"
           " solver, and check reflectances (< 1) and form-factor row sums (<= 1).";
    return Verdict::diverged;
  }
  if (k >= 2 * kRateWindow) {
    const double before = h[std::size_t(k - kRateWindow)];
    const double rate = std::pow(last / before, 1.0 / kRateWindow);
    if (rate > 1 && last > 10 * least) {
      *why = method + " diverged: the relative residual grew by a factor " + format_number(rate) + " per " +
             (entry_size == 1 ? std::string("sweep") : std::to_string(entry_size) + " shots") + " to " +
             format_number(last) + " after " + std::to_string(done) +
             " iterations, so the spectral radius of its iteration is >= 1."
             " Use the direct solver, and check reflectances (< 1) and form-factor row sums (<= 1).";
      return Verdict::diverged;
    }
    if (!(rate < 1)) {
      *why =
          method + " stagnated: the relative residual stayed at " + format_number(last) + " over the last " +
          std::to_string(kRateWindow * entry_size) + " iterations, above tol " + format_number(options.tol) +
          ": either tol is below the rounding level of this problem (loosen it) or the spectral radius of the"
          " iteration is about 1 (use the direct solver, check reflectances and form factors).";
      return Verdict::stagnated;
    }
    const double projected = double(done) + double(entry_size) * std::log(options.tol / last) / std::log(rate);
    if (projected > double(options.max_iterations)) {
      *why = method + " stopped early: at the observed rate " + format_number(rate) + " per " +
             (entry_size == 1 ? std::string("sweep") : std::to_string(entry_size) + " shots") +
             " the relative residual " + format_number(last) + " would reach tol " +
             format_number(options.tol) + " after about " + format_number(std::ceil(projected)) +
             " iterations, above max-iterations " + std::to_string(options.max_iterations) +
             ". Raise --max-iterations, use the direct solver, or loosen the tolerance.";
      return Verdict::too_slow;
    }
  }
  return Verdict::keep_going;
}

Verdict refusal(const StabilityCheck& check) {
  if (check.ok) return Verdict::keep_going;
  return check.status == SolveStatus::diverged ? Verdict::diverged : Verdict::too_slow;
}

void record_stability(const StabilityCheck& check, Solution& s) {
  s.info["spectral_radius_bound"] = check.radius.bound;
  s.info["spectral_radius_estimate"] = check.radius.estimate;
  if (check.radius.products > 0) s.info["spectral_radius_lower"] = check.radius.lower;
  if (std::isfinite(check.iterations_needed)) s.info["iterations_needed"] = check.iterations_needed;
}

}  // namespace radwalk

namespace radwalk {

void finish_iterative(Solution& s, const RadiosityProblem& p, const SolveOptions& options, PatchRgb B,
                      Verdict verdict, const std::string& why, long iterations, std::vector<double> history,
                      const std::string& unit) {
  std::string note;
  if (!B.allFinite()) {
    B = p.E;
    note = " The iterate overflowed; B was reset to E, which is not a solution.";
  }
  s.B = std::move(B);
  s.iterations = iterations;
  s.residual = relative_residual(p, s.B);
  if (options.record_history) {
    history.push_back(s.residual);
    s.residual_history = std::move(history);
  }
  const std::string summary = " after " + std::to_string(iterations) + " " + unit + ", relative residual " +
                              format_number(s.residual) + " (tol " + format_number(options.tol) + ").";
  if (s.residual <= options.tol) {
    s.status = SolveStatus::converged;
    s.message = s.method + " converged" + summary;
  } else if (verdict == Verdict::diverged) {
    s.status = SolveStatus::diverged;
    s.message = why + note;
  } else {
    s.status = SolveStatus::max_iterations;
    s.message = (verdict == Verdict::keep_going || verdict == Verdict::converged
                     ? s.method + " reached max-iterations " + std::to_string(options.max_iterations) + summary +
                           " Raise --max-iterations or use the direct solver."
                     : why + " Stopped" + summary) +
                note;
  }
}

}  // namespace radwalk
