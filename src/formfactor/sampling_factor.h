#pragma once
// How much smaller than the independent-sample formula (form_factor_noise.h) the variance of a row's gather is
// under the sampling F was traced with (jittered strata, Sobol points): measured on replicates.
//
// S rows are drawn at random among those with a non-zero formula variance, each row traced again R times with
// independent randomisations (the same options with other seeds: new strata, jitter and digital shifts), and for
// each part (rays, emitter columns) c is the mean over the rows of
//   c_i = sum_ch s_ich^2 / g_ich^2  /  sum_ch v_ich / g_ich^2,
// s^2 the sample variance of the R + 1 gathers g^(r) = (F^(r) B)_i (F's own row among them), v the mean of the
// formula's variance over the same R + 1 rows, g the mean gather (channels pooled by relative variance; rows with
// equal weights, so that no few bright rows decide). Its own relative error is about sqrt((2/R + var c_i) / S).
// Then the coverage factor kappa (form_factor_noise.h): the 95 % quantile over the chosen rows, their versions and
// channels of e^2 / ((1 + 1/R) (c_rays v_rays + c_emitter v_emitter)), e a version's deviation from the mean of the
// row's other versions, divided by 1.96^2.
// For independent rays (FormFactorOptions::stratified = false, no Sobol) c_rays = 1 exactly and no row is traced
// for it. Cost: S R rows' rays; S = min(eligible rows, max(128, N / 50)), R = max(2, ceil(256 / S)) (about 80 % of
// the rays of a 300-patch F, 25 % at 1000 patches, 4 % at 6400 patches and above; the smallest scenes need the
// rows for kappa's quantile). Reproducible: rows and seeds from the run's seed only.
#include <cstddef>

#include "core/types.h"
#include "formfactor/form_factor_noise.h"
#include "formfactor/form_factor_rows.h"
#include "formfactor/form_factors.h"
#include "patch/patch_set.h"
#include "visibility/visibility.h"

namespace radwalk {

struct SamplingCalibration {
  SamplingFactors factors;
  std::size_t rows = 0;    // S
  int replicates = 0;      // R
  long rays = 0;           // cosine and shadow rays traced for it
  double seconds = 0;
  bool rays_measured = false, emitter_measured = false;  // false: the factor is 1 by construction (or no such part)
};

// F (every row, the estimate traced with ff.options and ff.emitter_samples), ff's noise description (rays,
// emitter columns) and the radiosity B it gave (N x 3).
// Over MPI with F row-distributed (`blocks`), each process traces the chosen rows it holds and the results are
// shared (collective): the same factors, bit for bit, as one process.
SamplingCalibration calibrate_sampling_factors(const PatchSet& patches, const Visibility& visibility,
                                               const SparseF& F, const FormFactors& ff, const PatchRgb& B,
                                               const RowBlocks& blocks = {});

}  // namespace radwalk
