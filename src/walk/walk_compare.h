#pragma once
// compare_random_walks: runs each random-walk method R times (independent seeds) on one budget and tabulates
// accuracy, variance and efficiency, for `radwalk compare`.
//
// Budget: options.walk.walks_per_patch walks per estimated patch for gathering; the same total,
// walks_per_patch x (patches estimated), as particles for shooting. Run r uses seed options.walk.seed + r. Per patch,
// method and channel (long format):
//   mean        average of the R estimates of B
//   var         per-walk (per-particle) variance, averaged over the runs
//   var_se      standard error of var from the spread of the R runs' variances, sd_r(var_r) / sqrt(R); NaN for R = 1
//   var_theory  walk_variance.h (matrix kernel, N <= kMaxTheoryPatches), NaN otherwise
//   z           (mean - B_ref) / sqrt(var / walks): a unit normal if the method is unbiased and its variance
//               right; NaN without a reference
//   walks       walks of that patch's estimate over all runs (gather: R x walks; shoot: R x particles)
//   steps       destination samples of the method over all runs (all patches)
//   seconds     wall time of the method over all runs (all patches)
//   efficiency  1 / ((var / walks) x seconds): inverse variance of the pooled estimate per second
// Summary per method: mean and max |z| (about 0.80 and a few for an unbiased method), mean var / var_theory
// (about 1), run-to-run spread of the estimates over the predicted standard error (about 1, a check of the error
// bars), totals, and the efficiency of the mean variance.
#include <string>
#include <vector>

#include "patch/patch_set.h"
#include "solve/problem.h"
#include "visibility/visibility.h"
#include "walk/walk_options.h"

namespace radwalk {

struct CompareOptions {
  std::vector<WalkMethod> methods = all_walk_methods();
  int runs = 5;         // R >= 1
  WalkOptions walk;     // kernel, walks_per_patch (the budget), seed, patches (gathering), survival, and for the
                        // shooting methods sampler, replicates, direct_light, shadow_rays; method, particles and
                        // progress ignored
  bool theory = true;   // var_theory where computable
  bool progress = false;  // a progress line per method on stderr (core/progress.h)
};

// The one check of CompareOptions: InputError unless runs >= 1, some method is given, and the walk options are
// valid for every method (check_walk_options).
void check_compare_options(const CompareOptions& options, std::size_t patch_count);

struct CompareRow {
  int patch = 0;
  WalkMethod method = WalkMethod::gather_collision;
  int channel = 0;
  double mean = 0, var = 0, var_se = 0, var_theory = 0, z = 0;
  long walks = 0, steps = 0;
  double seconds = 0, efficiency = 0;
};

struct CompareSummary {
  WalkMethod method = WalkMethod::gather_collision;
  int runs = 0;
  long walks = 0, steps = 0;  // walks in total (all runs, all estimated patches), destination samples
  long walks_per_estimate = 0;  // walks behind each patch's pooled estimate (as CompareRow::walks)
  double seconds = 0;
  double mean_abs_z = 0, max_abs_z = 0;
  double var_ratio = 0;      // mean over rows of var / var_theory (NaN if no theory)
  double spread_ratio = 0;   // mean over rows of (sd of the R estimates) / (mean per-run standard error); NaN if R < 2
  double mean_var = 0;       // mean per-walk variance over rows
  double efficiency = 0;     // walks / (mean_var x seconds)
};

struct CompareResult {
  std::vector<CompareRow> rows;
  std::vector<CompareSummary> summary;
};

// B_reference: the exact solution for the same F (e.g. the direct solver); empty = dense_radiosity when
// N <= kMaxTheoryPatches (and the kernel is the matrix kernel), else z is NaN. Throws InputError on invalid
// options (check_compare_options).
CompareResult compare_random_walks(const RadiosityProblem& problem, const PatchSet* patches,
                                   const Visibility* visibility, const CompareOptions& options,
                                   const PatchRgb& B_reference = PatchRgb());

// The summary as an aligned text table, one line per method.
std::string format_compare_summary(const std::vector<CompareSummary>& summary);

}  // namespace radwalk
