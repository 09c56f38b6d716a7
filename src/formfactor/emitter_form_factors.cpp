#include "formfactor/emitter_form_factors.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "core/rng.h"
#include "formfactor/point_polygon_form_factor.h"
#include "formfactor/visible_form_factor.h"

namespace radwalk {

std::vector<std::size_t> emitter_patches(const PatchSet& patches) {
  std::vector<std::size_t> emitters;
  for (std::size_t e = 0; e < patches.size(); ++e)
    if (patches.E[e].maxCoeff() > 0) emitters.push_back(e);
  return emitters;
}

std::vector<EmitterEntry> estimate_emitter_row(const PatchSet& patches, const VisibleFormFactor& visible,
                                               const FormFactorOptions& options, long shadow_samples_per_patch,
                                               const std::vector<std::size_t>& emitters, std::size_t i, long& rays) {
  // The columns this row can see at all (some corner of i strictly in front of e's plane and some corner of e
  // strictly in front of i's plane: otherwise F(x -> e) = 0 for every x of i), the samples split evenly over them.
  std::vector<EmitterEntry> entries;
  for (std::size_t e : emitters)
    if (e != i && patch_may_see(patches, i, e)) entries.push_back({e, 0.0, 0.0});
  if (entries.empty()) return entries;
  const long M = std::max<long>(1, shadow_samples_per_patch / static_cast<long>(entries.size()));
  for (EmitterEntry& entry : entries) {
    Rng rng = stream(options.seed, StreamDomain::emitter_form_factor, i, entry.column);
    SobolShift shift;
    for (auto& w : shift.word) w = rng.next_u32();
    const VisibleFormFactor::Estimate estimate = visible.estimate_with_spread(i, entry.column, M, shift, rays);
    entry.value = estimate.mean;
    entry.variance = estimate.variance_of_mean;
  }
  return entries;
}

EmitterSampleChoice choose_emitter_samples(const PatchSet& patches, const FormFactorOptions& options,
                                           long requested) {
  if (requested >= 0) return {requested, requested > 0 ? "as requested" : "off as requested"};
  if (requested != kAutoEmitterSamples)
    throw InputError("form factors: emitter samples must be >= 0 or auto, got " + std::to_string(requested));
  const std::size_t N = patches.size();
  if (N == 0) return {0, "off: no patches"};
  double rays = 0;
  for (std::size_t i = 0; i < N; ++i) rays += ray_count(options, patches.area[i]);
  const long M = std::max<long>(1, std::lround(rays / double(N) / 3));
  const std::vector<std::size_t> emitters = emitter_patches(patches);
  const std::size_t m = emitters.size();
  if (m == 0) return {0, "off: the scene has no emitter"};
  double emitting = 0;
  for (std::size_t e : emitters) emitting += patches.area[e];
  if (emitting > kMaxEmitterAreaFraction * patches.total_area())
    return {0, "off: the emitters cover " + std::to_string(static_cast<int>(std::lround(100 * emitting / patches.total_area()))) +
                   " % of the area (the cosine rays sample large emitters well; the emitter columns pay off for small "
                   "lights)"};
  if (static_cast<double>(m) > static_cast<double>(M))
    return {0, "off: " + std::to_string(m) + " emitter patches, more than the " + std::to_string(M) +
                   " shadow samples a row would have (at least one each)"};
  if (static_cast<double>(N) * static_cast<double>(m) > kMaxEmitterEntries)
    return {0, "off: " + std::to_string(N) + " rows x " + std::to_string(m) + " emitter columns is above " +
                   std::to_string(static_cast<long>(kMaxEmitterEntries)) + " entries"};
  return {M, "auto: a third of the mean cosine rays per patch"};
}

FormFactors estimate_form_factors_with_emitters(const PatchSet& patches, const Visibility& visibility,
                                                const FormFactorOptions& options, long emitter_request) {
  const long samples = choose_emitter_samples(patches, options, emitter_request).samples;
  FormFactors ff = estimate_form_factors(patches, visibility, options);
  if (samples > 0) ff = replace_emitter_columns(std::move(ff), patches, visibility, samples).form_factors;
  return ff;
}

EmitterFormFactors estimate_emitter_form_factors(const PatchSet& patches, const Visibility& visibility,
                                                 const FormFactorOptions& options, long shadow_samples_per_patch) {
  return replace_emitter_columns(estimate_form_factors(patches, visibility, options), patches, visibility,
                                 shadow_samples_per_patch);
}

EmitterFormFactors replace_emitter_columns(FormFactors form_factors, const PatchSet& patches,
                                           const Visibility& visibility, long shadow_samples_per_patch) {
  if (shadow_samples_per_patch < 1)
    throw InputError("form factors: shadow samples per patch must be >= 1, got " +
                     std::to_string(shadow_samples_per_patch));
  EmitterFormFactors out;
  out.form_factors = std::move(form_factors);
  out.form_factors.emitter_samples = shadow_samples_per_patch;
  const FormFactorOptions& options = out.form_factors.options;
  const std::size_t N = patches.size();
  // The rows this process holds (all of them unless F is row-distributed over MPI): only those are replaced, with
  // the same streams, so row i is the same bits on the rank that holds it as on one process.
  const distributed::Range held = own_rows(out.form_factors.row_blocks, N);
  const std::vector<std::size_t> emitters = emitter_patches(patches);
  std::vector<std::int32_t> column_of(N, -1);  // emitter rank of a patch, -1 for a non-emitter
  for (std::size_t k = 0; k < emitters.size(); ++k) column_of[emitters[k]] = static_cast<std::int32_t>(k);
  out.emitter_columns = emitters.size();
  for (std::size_t e : emitters) out.form_factors.emitter_columns.push_back(static_cast<std::int32_t>(e));
  if (emitters.empty()) return out;
  const std::size_t m = emitters.size();
  // The replaced entries, row by row (N x m), their variances, and the rays per row.
  std::vector<double> value(N * m, 0.0), variance(N * m, 0.0);
  std::vector<long> rays(N, 0);
  const VisibleFormFactor visible(patches, visibility);
  parallel_for(
      held.end - held.begin,
      [&](std::size_t q) {
        const std::size_t i = held.begin + q;
        for (const EmitterEntry& entry :
             estimate_emitter_row(patches, visible, options, shadow_samples_per_patch, emitters, i, rays[i])) {
          const auto k = static_cast<std::size_t>(column_of[entry.column]);
          value[i * m + k] = std::max(0.0, entry.value);
          variance[i * m + k] = entry.variance;
        }
      },
      1);
  for (long r : rays) out.shadow_rays += r;
  // The variances as a sparse N x N matrix (emitter columns only; an entry wherever the row sees the emitter).
  std::vector<Eigen::Triplet<float>> triplets;
  for (std::size_t i = 0; i < N; ++i)
    for (std::size_t k = 0; k < m; ++k)
      if (variance[i * m + k] > 0)
        triplets.emplace_back(static_cast<int>(i), static_cast<int>(emitters[k]),
                              static_cast<float>(variance[i * m + k]));
  SparseF V(static_cast<Eigen::Index>(N), static_cast<Eigen::Index>(N));
  V.setFromTriplets(triplets.begin(), triplets.end());
  out.form_factors.emitter_variance = std::move(V);
  // Rebuild the CSR: each row keeps its non-emitter entries and takes its emitter entries from `value`
  // (columns stay sorted: a merge of the two sorted lists).
  const SparseF& F = out.form_factors.F;
  std::vector<std::int32_t> outer(N + 1, 0), inner;
  std::vector<float> values;
  inner.reserve(static_cast<std::size_t>(F.nonZeros()) + N);
  values.reserve(inner.capacity());
  for (std::size_t i = 0; i < N; ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    std::size_t k = 0;  // next emitter column to insert
    auto insert_emitters_below = [&](std::size_t limit) {
      for (; k < m && emitters[k] < limit; ++k)
        if (value[i * m + k] > 0) {
          inner.push_back(static_cast<std::int32_t>(emitters[k]));
          values.push_back(static_cast<float>(value[i * m + k]));
        }
    };
    for (SparseF::InnerIterator it(F, row); it; ++it) {
      const auto j = static_cast<std::size_t>(it.col());
      insert_emitters_below(j);
      if (column_of[j] >= 0) continue;  // the cosine rays' estimate of an emitter entry: replaced
      inner.push_back(static_cast<std::int32_t>(j));
      values.push_back(it.value());
    }
    insert_emitters_below(N);
    outer[i + 1] = static_cast<std::int32_t>(inner.size());
  }
  SparseF G(static_cast<Eigen::Index>(N), static_cast<Eigen::Index>(N));
  G.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
  std::copy(outer.begin(), outer.end(), G.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), G.innerIndexPtr());
  std::copy(values.begin(), values.end(), G.valuePtr());
  out.form_factors.F = std::move(G);
  return out;
}

}  // namespace radwalk
