#include "formfactor/sampling_factor.h"

#include <algorithm>
#include <vector>

#include "core/check.h"
#include "core/parallel.h"
#include "core/rng.h"
#include "core/timer.h"
#include "formfactor/emitter_form_factors.h"
#include "formfactor/visible_form_factor.h"

namespace radwalk {
namespace {

// At least 2 replicates per row, more where there are few rows, so that the factor rests on at least 64 rows traced
// again.
constexpr int kMinReplicates = 2;
constexpr std::size_t kMinTracedRows = 64;

// The seed of replicate r (r >= 1) of a run with seed `seed`: any value other than the run's own gives independent
// streams; mixed so that the replicates of seed s and the run with seed s + 1 do not share streams.
std::uint64_t replicate_seed(std::uint64_t seed, int r) { return mix64(seed ^ mix64(0x5eedULL + std::uint64_t(r))); }

// One row's gather with its variance parts, from F's own row.
RowGather gather_of_stored_row(const SparseF& F, const FormFactors& ff, const std::vector<char>& replaced,
                               const PatchRgb& B, std::size_t i) {
  RowGather g;
  const auto row = static_cast<Eigen::Index>(i);
  for (SparseF::InnerIterator it(F, row); it; ++it) {
    const Rgb b = B.row(it.col()).transpose();
    if (replaced[static_cast<std::size_t>(it.col())]) {
      const float variance = ff.emitter_variance.rows() ? ff.emitter_variance.coeff(row, it.col()) : 0.0f;
      g.add_emitter_entry(it.value(), variance, b);
    } else {
      g.add_ray_entry(it.value(), b);
    }
  }
  return g;
}

// The same for row i traced again with `options` (another seed).
RowGather gather_of_traced_row(const PatchSet& patches, const Visibility& visibility, const VisibleFormFactor& visible,
                               const FormFactors& ff, const FormFactorOptions& options,
                               const std::vector<std::size_t>& emitters, const std::vector<char>& replaced,
                               const PatchRgb& B, std::size_t i, long& rays) {
  RowGather g;
  const FormFactorRow row = trace_form_factor_row(patches, visibility, options, i);
  rays += row.rays;
  for (std::size_t q = 0; q < row.cols.size(); ++q)
    if (!replaced[static_cast<std::size_t>(row.cols[q])])
      g.add_ray_entry(double(row.counts[q]) / row.rays, B.row(row.cols[q]).transpose());
  if (ff.emitter_samples > 0)
    for (const EmitterEntry& e :
         estimate_emitter_row(patches, visible, options, ff.emitter_samples, emitters, i, rays))
      g.add_emitter_entry(std::max(0.0, e.value), e.variance, B.row(static_cast<Eigen::Index>(e.column)).transpose());
  return g;
}

}  // namespace

SamplingCalibration calibrate_sampling_factors(const PatchSet& patches, const Visibility& visibility,
                                               const SparseF& F, const FormFactors& ff, const PatchRgb& B) {
  Timer timer;
  SamplingCalibration out;
  const std::size_t N = patches.size();
  RADWALK_CHECK(has_noise_model(ff));
  RADWALK_CHECK_EQ(static_cast<std::size_t>(F.rows()), N);
  const bool rays_correlated = ff.options.stratified || ff.options.sobol;
  const bool emitter_part = ff.emitter_samples > 0 && !ff.emitter_columns.empty();
  if (!rays_correlated && !emitter_part) return out;
  std::vector<char> replaced(N, 0);
  for (std::int32_t e : ff.emitter_columns) replaced[static_cast<std::size_t>(e)] = 1;

  // The eligible rows (some formula variance) and S of them drawn without replacement.
  std::vector<std::size_t> eligible;
  for (std::size_t i = 0; i < N; ++i) {
    if (ff.rays[i] == 0) continue;
    const RowGather g = gather_of_stored_row(F, ff, replaced, B, i);
    if ((g.ray_variance(ff.rays[i]) + g.emitter_variance()).maxCoeff() > 0 && g.gather().maxCoeff() > 0)
      eligible.push_back(i);
  }
  const std::size_t S = std::min(eligible.size(), std::max<std::size_t>(32, N / 50));
  Rng pick = stream(ff.options.seed, StreamDomain::error_estimate, 0, 0);
  for (std::size_t k = 0; k < S; ++k)
    std::swap(eligible[k], eligible[k + pick.uniform_index(std::uint32_t(eligible.size() - k))]);
  eligible.resize(S);
  std::sort(eligible.begin(), eligible.end());
  if (S == 0) return out;

  const int kReplicates = std::max<int>(kMinReplicates, int((kMinTracedRows + S - 1) / S));
  // Gathers of the R + 1 versions of each chosen row (version 0: F's own).
  const std::vector<std::size_t> emitters = emitter_patches(patches);
  const VisibleFormFactor visible(patches, visibility);
  std::vector<RowGather> gathers(S * (kReplicates + 1));
  std::vector<long> rays(S, 0);
  parallel_for(S, [&](std::size_t k) {
    const std::size_t i = eligible[k];
    gathers[k * (kReplicates + 1)] = gather_of_stored_row(F, ff, replaced, B, i);
    for (int r = 1; r <= kReplicates; ++r) {
      FormFactorOptions options = ff.options;
      options.seed = replicate_seed(ff.options.seed, r);
      gathers[k * (kReplicates + 1) + std::size_t(r)] =
          gather_of_traced_row(patches, visibility, visible, ff, options, emitters, replaced, B, i, rays[k]);
    }
  }, 1);

  // Per row the ratio of the replicates' spread to the formula (channels pooled by relative variance), averaged over
  // the rows with equal weights.
  double spread_rays = 0, formula_rays = 0, spread_emitter = 0, formula_emitter = 0;
  for (std::size_t k = 0; k < S; ++k) {
    const RowGather* g = &gathers[k * (kReplicates + 1)];
    const double n = ff.rays[eligible[k]];
    Rgb mean_ray = Rgb::Zero(), mean_emitter = Rgb::Zero(), v_ray = Rgb::Zero(), v_emitter = Rgb::Zero();
    for (int r = 0; r <= kReplicates; ++r) {
      mean_ray += g[r].ray_gather();
      mean_emitter += g[r].emitter_gather();
      v_ray += g[r].ray_variance(n);
      v_emitter += g[r].emitter_variance();
    }
    const double versions = kReplicates + 1;
    mean_ray /= versions, mean_emitter /= versions, v_ray /= versions, v_emitter /= versions;
    Rgb s_ray = Rgb::Zero(), s_emitter = Rgb::Zero();
    for (int r = 0; r <= kReplicates; ++r) {
      s_ray += (g[r].ray_gather() - mean_ray).square();
      s_emitter += (g[r].emitter_gather() - mean_emitter).square();
    }
    s_ray /= versions - 1, s_emitter /= versions - 1;
    double row_spread_rays = 0, row_formula_rays = 0, row_spread_emitter = 0, row_formula_emitter = 0;
    for (int c = 0; c < 3; ++c) {
      const double g2 = (mean_ray[c] + mean_emitter[c]) * (mean_ray[c] + mean_emitter[c]);
      if (!(g2 > 0)) continue;
      row_spread_rays += s_ray[c] / g2, row_formula_rays += v_ray[c] / g2;
      row_spread_emitter += s_emitter[c] / g2, row_formula_emitter += v_emitter[c] / g2;
    }
    if (row_formula_rays > 0) spread_rays += row_spread_rays / row_formula_rays, formula_rays += 1;
    if (row_formula_emitter > 0) spread_emitter += row_spread_emitter / row_formula_emitter, formula_emitter += 1;
  }
  if (rays_correlated && formula_rays > 0) {
    out.factors.rays = spread_rays / formula_rays;
    out.rays_measured = true;
  }
  if (emitter_part && formula_emitter > 0) {
    out.factors.emitter = spread_emitter / formula_emitter;
    out.emitter_measured = true;
  }
  out.rows = S;
  out.replicates = kReplicates;
  for (long r : rays) out.rays += r;
  out.seconds = timer.seconds();
  return out;
}

}  // namespace radwalk
