#include "walk/walk_compare.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <sstream>
#include <string>

#include "core/check.h"
#include "core/error.h"
#include "core/moments.h"
#include "core/progress.h"
#include "walk/random_walk_solver.h"
#include "walk/walk_variance.h"

namespace radwalk {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The options of one method's runs: the budget as its count, walks_per_patch x (patches estimated) particles
// for shooting.
WalkOptions method_options(const CompareOptions& options, WalkMethod method, std::size_t patch_count) {
  WalkOptions wo = options.walk;
  wo.method = method;
  if (is_gathering(method)) {  // the sampler's options are the shooting methods' (walk_options.h)
    wo.sampler = WalkSampler::random;
    wo.direct_light = false;
  }
  // Stochastic Jacobi scores every arrival (shoot-collision only): the other shooting estimators run with the
  // Sobol sampler, its nearest (the same stratified emission and replicates).
  if (wo.sampler == WalkSampler::jacobi && method != WalkMethod::shoot_collision) wo.sampler = WalkSampler::sobol;
  wo.particles = options.walk.walks_per_patch *
                 static_cast<long>(options.walk.patches.empty() ? patch_count : options.walk.patches.size());
  wo.progress = false;
  return wo;
}

}  // namespace

void check_compare_options(const CompareOptions& options, std::size_t patch_count) {
  if (options.runs < 1) throw InputError("compare: runs = " + std::to_string(options.runs) + " (need >= 1)");
  if (options.methods.empty()) throw InputError("compare: no methods given");
  // The budget in walks (walks per patch x patches, over all runs) must be countable before anything multiplies it.
  const double budget = static_cast<double>(options.walk.walks_per_patch) * static_cast<double>(patch_count) *
                        static_cast<double>(options.runs);
  if (!(budget <= static_cast<double>(kMaxWalkCount)))
    throw InputError("compare: " + std::to_string(options.walk.walks_per_patch) + " walks per patch x " +
                     std::to_string(patch_count) + " patches x " + std::to_string(options.runs) +
                     " runs is more than the " + std::to_string(kMaxWalkCount) + " walks radwalk counts");
  for (WalkMethod method : options.methods) check_walk_options(method_options(options, method, patch_count), patch_count);
}

namespace {

CompareResult compare_unscaled(const RadiosityProblem& problem, const PatchSet* patches, const Visibility* visibility,
                               const CompareOptions& options, const PatchRgb& B_reference) {
  const std::size_t N = problem.size();
  check_compare_options(options, N);
  const auto n_rows = static_cast<Eigen::Index>(N);
  // Reference solution.
  PatchRgb B_ref = B_reference;
  const bool dense_ok = N <= kMaxTheoryPatches && problem.F.rows() == n_rows;
  if (B_ref.rows() == 0 && dense_ok) B_ref = dense_radiosity(problem);
  if (B_ref.rows() != 0) RADWALK_CHECK_EQ(B_ref.rows(), n_rows);  // the reference solves the same system
  std::vector<int> targets = options.walk.patches;
  if (targets.empty())
    for (std::size_t i = 0; i < N; ++i) targets.push_back(static_cast<int>(i));

  CompareResult result;
  for (const WalkMethod method : options.methods) {
    WalkOptions wo = method_options(options, method, N);
    const bool gather = is_gathering(method);
    const long count = gather ? wo.walks_per_patch : wo.particles;  // walks of one run per estimate
    std::optional<Progress> progress;
    if (options.progress)
      progress.emplace("compare " + std::string(method_name(method)),
                       static_cast<std::size_t>(options.runs) * walk_work_items(wo, N));
    // R runs: pooled estimates, variances and the run-to-run spread.
    PatchRgb sum_B = PatchRgb::Zero(n_rows, 3), sum_B2 = PatchRgb::Zero(n_rows, 3);
    PatchRgb sum_var = PatchRgb::Zero(n_rows, 3), sum_var2 = PatchRgb::Zero(n_rows, 3),
             sum_se = PatchRgb::Zero(n_rows, 3);
    long steps = 0;
    double seconds = 0;
    for (int r = 0; r < options.runs; ++r) {
      wo.seed = options.walk.seed + static_cast<std::uint64_t>(r);
      const Solution s = progress ? solve_random_walk(problem, patches, visibility, wo, *progress)
                                  : solve_random_walk(problem, patches, visibility, wo);
      sum_B += s.B;
      sum_B2 += s.B * s.B;
      sum_var += s.var;
      sum_var2 += s.var * s.var;
      sum_se += s.B_se;
      steps += s.steps;
      seconds += s.seconds;
    }
    if (progress) progress->finish();
    const double R = options.runs;
    PatchRgb var_theory;
    if (options.theory && wo.kernel == WalkKernel::matrix && dense_ok && B_ref.rows() == n_rows)
      var_theory = theoretical_variance(problem, wo, B_ref);
    // Rows and the summary.
    CompareSummary sum;
    sum.method = method;
    sum.runs = options.runs;
    sum.walks = count * options.runs * (gather ? static_cast<long>(targets.size()) : 1);
    sum.walks_per_estimate = count * options.runs;
    sum.steps = steps;
    sum.seconds = seconds;
    double z_abs = 0, ratio = 0, spread = 0, var_total = 0;
    long n_z = 0, n_ratio = 0, n_spread = 0, n_rows_m = 0;
    const long walks = count * options.runs;
    for (int i : targets)
      for (int c = 0; c < 3; ++c) {
        CompareRow row;
        row.patch = i;
        row.method = method;
        row.channel = c;
        row.mean = sum_B(i, c) / R;
        row.var = sum_var(i, c) / R;
        // The runs' variances are R independent estimates of the same per-walk variance: their spread is var's error.
        row.var_se = R > 1 ? std::sqrt(std::max(0.0, sum_var2(i, c) / R - row.var * row.var) / (R - 1)) : kNaN;
        row.var_theory = var_theory.rows() ? var_theory(i, c) : kNaN;
        const double se = std::sqrt(row.var / static_cast<double>(walks));
        // z of the pooled estimate; a zero-variance method is exact up to rounding (z = 0) or infinitely wrong.
        row.z = kNaN;
        if (B_ref.rows()) {
          const double diff = row.mean - B_ref(i, c);
          row.z = se > 0 ? diff / se
                         : (std::abs(diff) <= 1e-12 * std::abs(B_ref(i, c)) ? 0.0
                                                                            : std::numeric_limits<double>::infinity());
        }
        row.walks = walks;
        row.steps = steps;
        row.seconds = seconds;
        row.efficiency = row.var > 0 ? static_cast<double>(walks) / (row.var * seconds)
                                     : std::numeric_limits<double>::infinity();
        result.rows.push_back(row);
        // Summary tallies.
        var_total += row.var;
        ++n_rows_m;
        if (std::isfinite(row.z)) {
          z_abs += std::abs(row.z);
          sum.max_abs_z = std::max(sum.max_abs_z, std::abs(row.z));
          ++n_z;
        }
        if (std::isfinite(row.var_theory) && row.var_theory > 0) {
          ratio += row.var / row.var_theory;
          ++n_ratio;
        }
        if (options.runs >= 2 && sum_se(i, c) > 0) {
          const double sd = std::sqrt(mean_and_variance(sum_B(i, c), sum_B2(i, c), R).second);  // core/moments.h
          spread += sd / (sum_se(i, c) / R);
          ++n_spread;
        }
      }
    sum.mean_abs_z = n_z ? z_abs / static_cast<double>(n_z) : kNaN;
    if (!n_z) sum.max_abs_z = kNaN;
    sum.var_ratio = n_ratio ? ratio / static_cast<double>(n_ratio) : kNaN;
    sum.spread_ratio = n_spread ? spread / static_cast<double>(n_spread) : kNaN;
    sum.mean_var = n_rows_m ? var_total / static_cast<double>(n_rows_m) : kNaN;
    sum.efficiency = sum.mean_var > 0 ? static_cast<double>(walks) / (sum.mean_var * seconds)
                                      : std::numeric_limits<double>::infinity();
    result.summary.push_back(sum);
  }
  return result;
}

}  // namespace

// Scale before squaring (core/moments.h), as solve_random_walk does: with an emission far from 1 the runs compare
// the problem with E / s (s = moment_scale(max E), a power of two: exact) against B_reference / s, and the
// results are multiplied back: means by s, variances and their standard errors by s^2, efficiencies (1 / (var x
// seconds)) divided by s^2; z and the ratios do not change. The run-to-run spread of the variances squares a
// variance, which now fits a double whenever the variance does.
CompareResult compare_random_walks(const RadiosityProblem& problem, const PatchSet* patches,
                                   const Visibility* visibility, const CompareOptions& options,
                                   const PatchRgb& B_reference) {
  const double s = moment_scale(problem.max_emission());
  if (s == 1) return compare_unscaled(problem, patches, visibility, options, B_reference);
  RadiosityProblem scaled = problem;
  scaled.E /= s;
  CompareResult result = compare_unscaled(scaled, patches, visibility, options, PatchRgb(B_reference / s));
  const double s2 = s * s;
  for (CompareRow& row : result.rows) {
    row.mean *= s;
    row.var *= s2;
    row.var_se *= s2;
    row.var_theory *= s2;
    row.efficiency /= s2;
  }
  for (CompareSummary& summary : result.summary) {
    summary.mean_var *= s2;
    summary.efficiency /= s2;
  }
  return result;
}

std::string format_compare_summary(const std::vector<CompareSummary>& summary) {
  std::ostringstream out;
  char line[320];
  std::snprintf(line, sizeof line, "%-22s %5s %12s %13s %9s %9s %9s %9s %9s %12s %12s\n", "method", "runs", "walks",
                "steps", "seconds", "mean|z|", "max|z|", "var/theo", "spread", "mean var", "efficiency");
  out << line;
  for (const CompareSummary& s : summary) {
    std::snprintf(line, sizeof line, "%-22s %5d %12ld %13ld %9.3f %9.3f %9.3f %9.3f %9.3f %12.4g %12.4g\n",
                  std::string(method_name(s.method)).c_str(), s.runs, s.walks, s.steps, s.seconds, s.mean_abs_z, s.max_abs_z, s.var_ratio,
                  s.spread_ratio, s.mean_var, s.efficiency);
    out << line;
  }
  return out.str();
}

}  // namespace radwalk
