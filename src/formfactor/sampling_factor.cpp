#include "formfactor/sampling_factor.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/check.h"
#include "core/distributed.h"
#include "core/parallel.h"
#include "core/rng.h"
#include "core/timer.h"
#include "formfactor/emitter_form_factors.h"
#include "formfactor/visible_form_factor.h"

namespace radwalk {
namespace {

// At least 128 rows (all eligible ones if fewer) and 2 replicates per row, more where there are few rows, so that
// the factors rest on at least 256 rows traced again (the coverage factor is a quantile).
constexpr int kMinReplicates = 2;
constexpr std::size_t kMinRows = 128;
constexpr std::size_t kMinTracedRows = 256;
// The coverage the factor is matched to: 95 % of the deviations within 1.96 standard errors.
constexpr double kCoverage = 0.95;
constexpr double kCoverageQuantile = 1.959963984540054;

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

// The coverage factor kappa (form_factor_noise.h): with the factors c, each version r of a chosen row deviates from
// the mean of the row's other R versions by e = g_r - mean_{r' != r} g_r', whose variance is
// (1 + 1/R) (c_rays v_rays + c_emitter v_emitter) if the row's own reduction were c. kappa is the 95 % quantile of
// e^2 / that variance over the rows, versions and channels, divided by 1.96^2: the scale at which 95 % of the rows'
// deviations lie within 1.96 standard errors. 1 when there is nothing to measure.
double coverage_factor(const std::vector<double>& terms, std::size_t stride, std::size_t versions,
                       const SamplingFactors& c) {
  std::vector<double> t2;
  const double R = double(versions) - 1;
  for (std::size_t k = 0; k + stride <= terms.size(); k += stride) {
    const double* t = &terms[k];
    for (std::size_t ch = 0; ch < 3; ++ch) {
      const double v = (c.rays * t[5 + 3 * versions + ch] + c.emitter * t[8 + 3 * versions + ch]) * (1 + 1 / R);
      if (!(v > 0)) continue;
      double sum = 0;
      for (std::size_t r = 0; r < versions; ++r) sum += t[5 + 3 * r + ch];
      for (std::size_t r = 0; r < versions; ++r) {
        const double g = t[5 + 3 * r + ch], others = (sum - g) / R;
        t2.push_back((g - others) * (g - others) / v);
      }
    }
  }
  if (t2.empty()) return 1;
  const std::size_t q = std::min(t2.size() - 1, std::size_t(std::ceil(kCoverage * double(t2.size()))) - 1);
  std::nth_element(t2.begin(), t2.begin() + std::ptrdiff_t(q), t2.end());
  return t2[q] / (kCoverageQuantile * kCoverageQuantile);
}

}  // namespace

SamplingCalibration calibrate_sampling_factors(const PatchSet& patches, const Visibility& visibility,
                                               const SparseF& F, const FormFactors& ff, const PatchRgb& B,
                                               const RowBlocks& blocks) {
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
  // Over MPI each process judges the rows it holds and the verdicts are shared.
  const distributed::Range mine = own_rows(blocks, N);
  std::vector<char> is_eligible(N, 0);
  for (std::size_t i = mine.begin; i < mine.end; ++i) {
    if (ff.rays[i] == 0) continue;
    const RowGather g = gather_of_stored_row(F, ff, replaced, B, i);
    is_eligible[i] = (g.ray_variance(ff.rays[i]) + g.emitter_variance()).maxCoeff() > 0 && g.gather().maxCoeff() > 0;
  }
  if (!blocks.empty()) distributed::allgather_in_place(is_eligible.data(), 1, blocks);
  std::vector<std::size_t> eligible;
  for (std::size_t i = 0; i < N; ++i)
    if (is_eligible[i]) eligible.push_back(i);
  const std::size_t S = std::min(eligible.size(), std::max<std::size_t>(kMinRows, N / 50));
  Rng pick = stream(ff.options.seed, StreamDomain::error_estimate, 0, 0);
  for (std::size_t k = 0; k < S; ++k)
    std::swap(eligible[k], eligible[k + pick.uniform_index(std::uint32_t(eligible.size() - k))]);
  eligible.resize(S);
  std::sort(eligible.begin(), eligible.end());
  if (S == 0) return out;

  const int kReplicates = std::max<int>(kMinReplicates, int((kMinTracedRows + S - 1) / S));
  // Per chosen row (those this process holds; over MPI the rows are shared afterwards): the spread of its R + 1
  // versions' gathers (version 0: F's own) and the formula's mean variance, channels pooled by relative variance,
  // for each part, and the rays traced: {spread_rays, formula_rays, spread_emitter, formula_emitter, rays}; then the
  // versions' gathers (R + 1 x 3, both parts) and the formula's mean variance of each part (3 + 3), for the
  // coverage factor.
  const std::vector<std::size_t> emitters = emitter_patches(patches);
  const VisibleFormFactor visible(patches, visibility);
  const std::size_t versions_count = std::size_t(kReplicates) + 1;
  const std::size_t kTerms = 5 + 3 * versions_count + 6;
  std::vector<double> terms(S * kTerms, 0.0);
  const auto first = std::size_t(std::lower_bound(eligible.begin(), eligible.end(), mine.begin) - eligible.begin());
  const auto last = std::size_t(std::lower_bound(eligible.begin(), eligible.end(), mine.end) - eligible.begin());
  parallel_for(last - first, [&](std::size_t q) {
    const std::size_t k = first + q, i = eligible[k];
    std::vector<RowGather> g(std::size_t(kReplicates) + 1);
    long rays = 0;
    g[0] = gather_of_stored_row(F, ff, replaced, B, i);
    for (int r = 1; r <= kReplicates; ++r) {
      FormFactorOptions options = ff.options;
      options.seed = replicate_seed(ff.options.seed, r);
      g[std::size_t(r)] = gather_of_traced_row(patches, visibility, visible, ff, options, emitters, replaced, B, i, rays);
    }
    const double n = ff.rays[i];
    Rgb mean_ray = Rgb::Zero(), mean_emitter = Rgb::Zero(), v_ray = Rgb::Zero(), v_emitter = Rgb::Zero();
    for (const RowGather& x : g) {
      mean_ray += x.ray_gather();
      mean_emitter += x.emitter_gather();
      v_ray += x.ray_variance(n);
      v_emitter += x.emitter_variance();
    }
    const double versions = kReplicates + 1;
    mean_ray /= versions, mean_emitter /= versions, v_ray /= versions, v_emitter /= versions;
    Rgb s_ray = Rgb::Zero(), s_emitter = Rgb::Zero();
    for (const RowGather& x : g) {
      s_ray += (x.ray_gather() - mean_ray).square();
      s_emitter += (x.emitter_gather() - mean_emitter).square();
    }
    s_ray /= versions - 1, s_emitter /= versions - 1;
    double* t = &terms[k * kTerms];
    for (int c = 0; c < 3; ++c) {
      const double g2 = (mean_ray[c] + mean_emitter[c]) * (mean_ray[c] + mean_emitter[c]);
      if (!(g2 > 0)) continue;
      t[0] += s_ray[c] / g2, t[1] += v_ray[c] / g2, t[2] += s_emitter[c] / g2, t[3] += v_emitter[c] / g2;
    }
    t[4] = double(rays);
    for (std::size_t r = 0; r < versions_count; ++r)
      for (int c = 0; c < 3; ++c) t[5 + 3 * r + std::size_t(c)] = g[r].gather()[c];
    for (int c = 0; c < 3; ++c) {
      t[5 + 3 * versions_count + std::size_t(c)] = v_ray[c];
      t[8 + 3 * versions_count + std::size_t(c)] = v_emitter[c];
    }
  }, 1);
  if (!blocks.empty()) {
    std::vector<distributed::Range> chosen(blocks.size());
    for (std::size_t r = 0; r < blocks.size(); ++r)
      chosen[r] = {std::size_t(std::lower_bound(eligible.begin(), eligible.end(), blocks[r].begin) - eligible.begin()),
                   std::size_t(std::lower_bound(eligible.begin(), eligible.end(), blocks[r].end) - eligible.begin())};
    distributed::allgather_in_place(terms.data(), kTerms * sizeof(double), chosen);
  }

  // The mean over the rows of each row's ratio of the replicates' spread to the formula.
  double spread_rays = 0, formula_rays = 0, spread_emitter = 0, formula_emitter = 0;
  for (std::size_t k = 0; k < S; ++k) {
    const double* t = &terms[k * kTerms];
    if (t[1] > 0) spread_rays += t[0] / t[1], formula_rays += 1;
    if (t[3] > 0) spread_emitter += t[2] / t[3], formula_emitter += 1;
    out.rays += static_cast<long>(t[4]);
  }
  if (rays_correlated && formula_rays > 0) {
    out.factors.rays = spread_rays / formula_rays;
    out.rays_measured = true;
  }
  if (emitter_part && formula_emitter > 0) {
    out.factors.emitter = spread_emitter / formula_emitter;
    out.emitter_measured = true;
  }
  out.factors.coverage = coverage_factor(terms, kTerms, versions_count, out.factors);
  out.rows = S;
  out.replicates = kReplicates;
  out.seconds = timer.seconds();
  return out;
}

}  // namespace radwalk
