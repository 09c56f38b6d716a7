#pragma once
// Form factors by cosine-weighted ray shooting (Monte Carlo, unbiased).
//
// For patch i with n_i rays:  F_ij = (rays from i whose first hit is the FRONT of patch j) / n_i,
// an unbiased estimator of F_ij = (1/A_i) int_{A_i} int_{A_j} V cos(t_i) cos(t_j) / (pi r^2) dA_j dA_i, because a
// ray with a uniform origin on A_i (pdf 1/A_i) and a cosine-weighted direction (pdf cos(t_i)/pi) reaches the
// front of j with exactly that probability. Rays that leave the scene are counted in `escaped`, rays whose first
// hit is the back of a one-sided patch in `back_hits` (a two-sided face has a patch per side, so it gives none);
// neither enters F, so row sums are 1 - (escaped + back_hits)/n_i.
//
// Sampling (stratified, unbiased): with m = min(floor(sqrt(n_i)), 1024), the first m^2 rays take one jittered stratum each
// of the direction square (u3, u4) (cosine warp of sample_cosine_hemisphere) and, through a random permutation,
// one jittered stratum each of the origin square (u1, u2) (warp of sample_patch_point); the remaining
// n_i - m^2 rays are uniform. Each of the m^2 strata of either square has probability 1/m^2 and gets exactly one
// sample, so the mean over the rays is unbiased; its variance is at most the binomial variance
// F_ij (1 - F_ij) / n_i up to the Latin-hypercube factor m^2/(m^2 - 1) (Owen 1997), so binomial standard errors
// are (essentially) conservative. `stratified = false` draws all four numbers uniformly (pure binomial counts).
//
// Reproducible: patch i uses the stream (seed, form_factor_row, i) only (core/rng.h), so F is bit-identical for any thread count.
// Rays leave through spawn_ray (visibility/ray_offset.h). Parallel over patches (core/parallel.h); rows are
// assembled into CSR without a global sort or lock: each row's hits are sorted into (j, count) runs in place,
// then appended to F's arrays, reserved once (never copied). Memory: 8 bytes per non-zero of F (resident; the
// reservation for sum_i min(n_i, N) non-zeros costs address space only; over MPI, estimate_form_factor_rows: of
// the rank's own rows only) plus a working buffer of at most 16 M rays (8 bytes per ray).
#include <cstdint>
#include <vector>

#include "formfactor/form_factor_rows.h"
#include "formfactor/sparse_f.h"
#include "patch/patch_set.h"
#include "visibility/visibility.h"

namespace radwalk {

struct FormFactorOptions {
  long rays_per_patch = 1000;  // n_i when rays_per_area == 0
  double rays_per_area = 0;    // D > 0: n_i = max(min_rays, round(D * A_i)) (D in rays per unit area)
  long min_rays = 16;
  std::uint64_t seed = 1;
  bool stratified = true;
  // Randomised Sobol points instead of the strata: ray r of row i takes Sobol point r (core/sobol.h: (u1, u2) the
  // origin, (u3, u4) the cosine direction) with a digital shift of four words drawn first from the row's stream;
  // unbiased (each shifted point is uniform), stratified in all four dimensions together.
  bool sobol = false;
  // The order the rows are traced in, not what they hold: within each assembly block of consecutive rows, by the
  // Morton code of the patch centroids (core/morton.h), so that consecutive rows start from nearby patches and
  // their rays meet the same parts of the BVH while they are cached; false: in patch order. Every row has its own
  // stream, so F is the same bit for bit either way and for any thread count.
  bool morton_order = true;
};

struct FormFactors {
  SparseF F;                          // N x N, row i = where rays leaving i land (front faces only)
  std::vector<std::uint32_t> rays;     // n_i
  std::vector<std::uint32_t> escaped;  // rays from i that hit nothing
  std::vector<std::uint32_t> back_hits;  // rays from i whose first hit was the back of a patch
  // The analytic route (analytic_form_factors.h) leaves rays, escaped and back_hits empty and gives instead the
  // standard error of each row's sum from its visibility estimates (0 where every pair of the row was proven clear
  // or hidden); empty on the ray route.
  std::vector<double> row_std_error;
  // Over MPI: the rank blocks of F's rows when F holds only this rank's rows (form_factor_rows.h); empty when
  // every rank holds every row.
  RowBlocks row_blocks;
  // How F was estimated, for its error (form_factor_noise.h); rays is empty when F was read from a file. With
  // emitter columns (emitter_form_factors.h): the shadow samples per patch, the replaced columns (increasing) and
  // the variance of each replaced entry's estimate (N x N, non-zeros in those columns only); empty otherwise.
  FormFactorOptions options;
  long emitter_samples = 0;
  std::vector<std::int32_t> emitter_columns;
  SparseF emitter_variance;
  // With --enforce-closure (formfactor/closure.h): per row, max_j |F'_ij - F_ij| and the RMS change over its
  // entries; empty otherwise.
  std::vector<double> closure_max_change, closure_rms_change;
};

// One row of F exactly as estimate_form_factors traces it (the same stream, so the same rays): the columns hit
// (increasing) with their counts, and the ray outcomes. For replicates of a row with another seed
// (formfactor/sampling_factor.h).
struct FormFactorRow {
  std::vector<std::int32_t> cols;
  std::vector<std::uint32_t> counts;
  std::uint32_t rays = 0, escaped = 0, back_hits = 0;
};
FormFactorRow trace_form_factor_row(const PatchSet& patches, const Visibility& visibility,
                                    const FormFactorOptions& options, std::size_t i);

// n_i for a patch of area `area` under `options` (checked: InputError for options out of range).
std::uint32_t ray_count(const FormFactorOptions& options, double area);

// Estimates F for all patches. InputError for bad options (rays_per_patch < 1, negative or non-finite
// rays_per_area, min_rays < 1, more than 2^32 - 1 rays for a patch, more than 2^31 - 1 patches).
// Over MPI every rank gets the whole F (gather_whole_rows after estimate_form_factor_rows).
FormFactors estimate_form_factors(const PatchSet& patches, const Visibility& visibility,
                                  const FormFactorOptions& options = {});

// The same estimate, row-distributed over MPI (form_factor_rows.h): each rank traces and keeps the rows of its
// block (blocks of about equal rays, in row_blocks), so F holds the non-zeros of those rows only; rays, escaped
// and back_hits cover every patch on every rank. With one process it is estimate_form_factors (row_blocks empty).
FormFactors estimate_form_factor_rows(const PatchSet& patches, const Visibility& visibility,
                                      const FormFactorOptions& options = {});

}  // namespace radwalk
