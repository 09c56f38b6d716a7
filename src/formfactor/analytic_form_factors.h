#pragma once
// Form factors by the analytic route (docs/form-factors.md, "The analytic route"; docs/theory/polygon_form_factor.md):
//   F_ij = (G_ij / A_i) V_ij,   F_ji = (G_ij / A_j) V_ij,
// G_ij = A_i F_ij^unoccluded the exact exchange area of the pair by contour integration (polygon_form_factor.h),
// V_ij in [0, 1] the pair's visibility fraction
//   V_ij = int_i int_j G(x, y) V(x, y) dy dx / int_i int_j G(x, y) dy dx,   G = cos_x cos_y / (pi r^2),
// one value per unordered pair, so A_i F_ij = A_j F_ji holds by construction (to float rounding of the stored F).
//
// Pairs (patch_pair_tree.h): a dual traversal of a bounding-volume hierarchy of the patches prunes node pairs that
// lie behind each other's planes and, with options.cutoff = tau > 0, drops node pairs whose bound
// max(A_j) / (pi d^2) on every F_ij and F_ji of the pair (d the distance of their boxes) is at most tau; every
// other pair i < j that may see each other (patch_may_see) is computed. Dropped pairs are never silent: per row i,
// cutoff_bound[i] >= sum of the dropped F_ij, and cutoff_estimate[i] is their one-point unoccluded estimate, so in
// a closed unoccluded scene 1 - cutoff_bound[i] <= row sum i <= 1 (to rounding). With tau = 0 (the default) nothing
// is dropped: every pair with G_ij > 0 is an entry, in time N^2 for scenes whose patches all face each other, so
// the route then refuses more than options.max_patches patches (a one-line InputError); with tau > 0 the time is
// O(N log N + kept pairs) and there is no such limit.
// Completion (options.cutoff_rays = n > 0): the dropped pairs are then estimated instead of left out: row i traces n
// cosine-weighted rays (randomised Sobol points, the shift from stream(seed, analytic_visibility, i, i): b = a never
// names a pair), and each front hit on a patch j of a dropped pair counts; G_ij = (A_i c_ij + A_j c_ji) / (2 n) is
// an unbiased estimate of the occluded exchange area (E[c_ij / n] = F_ij with occlusion), reciprocal by
// construction, stored as an estimated entry with the binomial standard error of its two halves (a half of no
// hits adds no variance: an understatement for pairs hit from one side only). Rows of a closed scene then sum to 1
// in expectation, within their standard error; the cut-off's bound and estimate are still reported.
// Visibility (patch_shaft.h): V_ij = 1 exactly where no patch meets the pair's shaft, 0 exactly where one convex
// patch covers it; otherwise it is estimated from point pairs (x_s, y_s), x_s uniform on i's clipped polygon and
// y_s on j's (randomised Sobol points, digital shifts drawn from stream(seed, analytic_visibility, i, j)), with
// w_s = g(x_s, y_s) / E[g], g = cos_x cos_y / (pi r^2), E[g] = G_ij / (A'_i A'_j) known exactly (A' the clipped
// areas), and v_s = 1 when the segment x_s -> y_s is unoccluded. Both
//   V^ = (1 / M) sum_s w_s v_s              ("visible" form: exactly 0 when every segment is blocked) and
//   V^ = 1 - (1 / M) sum_s w_s (1 - v_s)     ("blocked" form: exactly 1 when none is)
// are unbiased for V_ij. A pilot of 16 point pairs (its own shift) chooses the form (the blocked form when at least
// half of the pilot's weight is visible) and M: the least power of 2 >= min_visibility_samples whose predicted
// standard error sqrt(pilot variance / M) is at most visibility_tolerance, at most max_visibility_samples; the
// estimate then uses M fresh point pairs (the second shift), so the data-dependent choice does not bias it. The
// standard error is the sample standard deviation / sqrt(M) (conservative for Sobol points), at least 1 / M (the
// sample variance is 0 when every sample agreed). A negative blocked-form estimate is stored as 0 (the only
// bias; the pilot makes it rare). The row's standard error is sqrt(sum_j (G_ij se_ij / A_i)^2).
// Rows above 1: estimates can push a row's sum above 1 in an occluded scene (the unoccluded G of a row sum above 1
// when patches hide each other). Rows are taken in order; a row whose sum exceeds 1 + 1e-12 has its estimated
// entries (and, if that is not enough, all) scaled down to sum 1, each change applied to G_ij, so to both F_ij and
// F_ji: reciprocity kept, entries only decrease, so rows already taken stay at most 1. Counted in rows_scaled.
// Reproducible: every pair's points come from its own stream, so F is bit-identical for any thread count.
// Memory: O(non-zeros) (about 24 bytes per pair while assembling, then F's 8 bytes per entry).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "formfactor/form_factors.h"
#include "patch/patch_set.h"
#include "visibility/visibility.h"

namespace radwalk {

struct AnalyticFormFactorOptions {
  std::uint64_t seed = 1;
  long min_visibility_samples = 32;    // the least M of a sampled pair (a power of 2, >= 2)
  long max_visibility_samples = 1024;  // at most this many (a power of 2, >= min_visibility_samples)
  double visibility_tolerance = 0.05;  // the standard error of a visibility fraction that M aims at
  std::size_t max_patches = 20000;     // without a cut-off, more patches than this are refused (time N^2)
  double cutoff = 0;                   // tau in [0, 1): pairs whose F bound is at most tau are dropped (reported)
  long cutoff_rays = 0;                // > 0 (needs cutoff > 0): the dropped pairs estimated by this many cosine rays a row
};

struct AnalyticFormFactors {
  FormFactors form_factors;        // F; row_std_error per row; rays, escaped, back_hits empty
  // The standard error of each stored entry of F (aligned with F's values): G_ij se_ij / A_i for a pair whose
  // visibility was estimated, 0 where it was proven.
  std::vector<float> entry_std_error;
  std::uint64_t pairs = 0;         // pairs with G_ij > 0 (each gives F_ij and F_ji)
  std::uint64_t clear_pairs = 0;   // V = 1 proven by the shaft test
  std::uint64_t hidden_pairs = 0;  // V = 0 proven by a covering patch
  std::uint64_t sampled_pairs = 0; // V estimated by rays
  std::uint64_t visibility_rays = 0;
  std::size_t rows_scaled = 0;     // rows brought down to sum 1 (see above)
  double largest_row_excess = 0;   // the largest row sum - 1 before that, 0 when none exceeded 1
  double cutoff = 0;                     // the cut-off tau used
  std::uint64_t dropped_pairs = 0;       // unordered pairs dropped by the cut-off (facing or not)
  std::vector<double> cutoff_bound;      // per row i: an upper bound on the sum of the dropped F_ij (0 without)
  std::vector<double> cutoff_estimate;   // per row i: their one-point estimate without occlusion
  std::uint64_t cutoff_rays = 0;         // cosine rays traced for the completion (cutoff_rays > 0)
  std::uint64_t completed_pairs = 0;     // dropped pairs given an entry by them
};

// InputError for options out of range, more than max_patches patches or more than 2^31 - 1 non-zeros.
// Over MPI every rank computes the whole F (row_blocks empty).
AnalyticFormFactors analytic_form_factors(const PatchSet& patches, const Visibility& visibility,
                                          const AnalyticFormFactorOptions& options = {});

}  // namespace radwalk
