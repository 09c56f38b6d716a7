#pragma once
// The Monte Carlo noise of a traced F as the radiosity sees it: the variance of each row's gather g_i = (F B)_i.
//
// Row i of F is estimated from n_i cosine rays (form_factors.h), F_ik = (rays landing on the front of k) / n_i, so
// its gather g_i = sum_k F_ik B_k is the mean over the rays of y_s = B_{k(s)} (y_s = 0 for a ray that escapes, hits
// a back, or lands on an emitter whose column is replaced). For independent rays
//   Var(g_i) = (sum_k F_ik B_k^2 - (sum_k F_ik B_k)^2) / n_i            (sums over the counted columns k),
// evaluated with the estimated F (the plug-in multinomial variance). The replaced emitter columns
// (emitter_form_factors.h) come from samples of their own, independent of the rays and of each other, and add
//   sum_e B_e^2 Var(F_ie)                                                (Var(F_ie) from the entry's own samples).
// Rows are traced from independent streams, so the gathers of different rows are independent. Stratified rays and
// Sobol points are not independent samples: they make each part smaller by a factor c <= 1 (about 0.55 and 0.4 for
// the rays on the Cornell box at 1000 rays per patch) that formfactor/sampling_factor.h measures, so
//   Var(g_i) = c_rays * (ray part) + c_emitter * (emitter part).
// Derivation and checks: docs/theory/error_estimate.md.
#include "core/types.h"
#include "formfactor/form_factor_rows.h"
#include "formfactor/form_factors.h"

namespace radwalk {

// The reduction c is not the same in every row (on the Cornell box at 1000 Sobol rays per patch the rows' own c
// spread from 0.07 to 0.30, 10 % to 90 %, and no row statistic tried predicted it), so one factor per part gives
// the right mean variance but too few rows within 1.96 standard errors: the rows whose c is large fall outside. The
// coverage factor kappa, measured on the same replicated rows, scales the variance so that 95 % of the rows'
// deviations lie within 1.96 standard errors:
//   Var(g_i) = kappa (c_rays * (ray part) + c_emitter * (emitter part))      (per patch: B_se),
// while a sum over many rows (a measurement M) averages the rows' c and takes kappa = 1.
struct SamplingFactors {
  double rays = 1;      // c of the cosine rays' part
  double emitter = 1;   // c of the emitter columns' part
  double coverage = 1;  // kappa
};

// The two parts of Var(g_i), per patch and channel, before the sampling factors.
struct GatherVariance {
  PatchRgb rays;
  PatchRgb emitter;
  // kappa (c_rays rays + c_emitter emitter): the variance per row for per-patch standard errors.
  PatchRgb scaled(const SamplingFactors& c) const { return c.coverage * (c.rays * rays + c.emitter * emitter); }
};

// True when ff records how F was traced (ray counts), so that its noise can be estimated; false for F read from a
// file.
bool has_noise_model(const FormFactors& ff);

// The parts above for the rows this process holds of F (N x N, the estimate; F may have been moved out of ff, whose
// rays, emitter columns and emitter variances describe it) and radiosity B (N x 3). Rows without rays get 0.
// Reciprocity averaging (--reciprocity) changes F after the rays: the formula then describes the traced F, whose
// noise the averaging only reduces (an upper bound).
// Over MPI with F row-distributed (`blocks` non-empty) each process computes its rows and every process gets all
// (collective).
GatherVariance gather_variance(const SparseF& F, const FormFactors& ff, const PatchRgb& B,
                               const RowBlocks& blocks = {});

// One row's gather and its variance parts, accumulated entry by entry (by gather_variance, and by the replicates
// of sampling_factor.h for rows traced again).
class RowGather {
 public:
  // A counted entry F_ik (a fraction of the row's rays) of column k with radiosity B_k.
  void add_ray_entry(double F_ik, const Rgb& B_k) {
    ray_gather_ += F_ik * B_k;
    ray_square_ += F_ik * B_k * B_k;
  }
  // A replaced emitter entry F_ie with the variance of its estimate.
  void add_emitter_entry(double F_ie, double variance, const Rgb& B_e) {
    emitter_gather_ += F_ie * B_e;
    emitter_variance_ += variance * B_e * B_e;
  }
  Rgb gather() const { return ray_gather_ + emitter_gather_; }
  Rgb ray_gather() const { return ray_gather_; }
  Rgb emitter_gather() const { return emitter_gather_; }
  // The ray part of Var(g_i) for n rays (0 for n = 0), and the emitter part.
  Rgb ray_variance(double n) const {
    return n > 0 ? ((ray_square_ - ray_gather_ * ray_gather_) / n).max(0.0) : Rgb::Zero().eval();
  }
  Rgb emitter_variance() const { return emitter_variance_; }

 private:
  Rgb ray_gather_ = Rgb::Zero(), ray_square_ = Rgb::Zero();
  Rgb emitter_gather_ = Rgb::Zero(), emitter_variance_ = Rgb::Zero();
};

}  // namespace radwalk
