#include "formfactor/form_factor_diagnostics.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>

#include "core/check.h"
#include "core/parallel.h"

namespace radwalk {

FormFactorDiagnostics diagnose_form_factors(const SparseF& F, const std::vector<double>& area,
                                            const std::vector<std::uint32_t>& rays,
                                            const std::vector<std::uint32_t>& back_hits) {
  const std::size_t N = std::size_t(F.rows());
  RADWALK_CHECK_EQ(F.cols(), F.rows());
  RADWALK_CHECK_EQ(area.size(), N);
  if (!rays.empty()) RADWALK_CHECK_EQ(rays.size(), N);
  if (!back_hits.empty()) RADWALK_CHECK_EQ(back_hits.size(), N);

  FormFactorDiagnostics d;
  d.row_sum.assign(N, 0.0);
  d.reciprocity_error.assign(N, 0.0);
  if (!rays.empty()) d.row_std_error.assign(N, 0.0);
  if (!rays.empty() && !back_hits.empty()) d.back_hit_fraction.assign(N, 0.0);
  // one_sided[j]: some F_ij > 0 with F_ji absent, so row j (whose column i is then F_ij > 0 against F_ji = 0)
  // has a reciprocity error of 1; set from row i's pass, read after all rows are done.
  std::vector<std::atomic<std::uint8_t>> one_sided(N);
  SparseF compressed;  // only for a matrix still in Eigen's uncompressed (insert) mode
  const SparseF* G = &F;
  if (!F.isCompressed()) {
    compressed = F;
    compressed.makeCompressed();
    G = &compressed;
  }
  const std::int32_t* outer = G->outerIndexPtr();
  const std::int32_t* inner = G->innerIndexPtr();
  const float* value = G->valuePtr();

  parallel_for(N, [&](std::size_t i) {
    // Closure and the largest binomial variance of the row.
    double sum = 0, max_var = 0;
    for (std::int32_t k = outer[i]; k < outer[i + 1]; ++k) {
      sum += value[k];
      max_var = std::max(max_var, double(value[k]) * (1.0 - double(value[k])));
    }
    d.row_sum[i] = sum;
    if (!rays.empty()) d.row_std_error[i] = std::sqrt(max_var / rays[i]);
    if (!d.back_hit_fraction.empty()) d.back_hit_fraction[i] = double(back_hits[i]) / rays[i];

    // Reciprocity over the j of row i: F_ji by binary search in row j (0 when absent).
    double worst = 0;
    for (std::int32_t k = outer[i]; k < outer[i + 1]; ++k) {
      const std::int32_t j = inner[k];
      const std::int32_t* row_j = inner + outer[j];
      const std::int32_t* end_j = inner + outer[j + 1];
      const std::int32_t* at = std::lower_bound(row_j, end_j, std::int32_t(i));
      const bool found = at != end_j && *at == std::int32_t(i);
      const double gij = area[i] * value[k], gji = found ? area[std::size_t(j)] * value[at - inner] : 0.0;
      if (!found && gij > 0) one_sided[std::size_t(j)].store(1, std::memory_order_relaxed);
      const double m = std::max(gij, gji);
      if (m > 0) worst = std::max(worst, std::abs(gij - gji) / m);
    }
    d.reciprocity_error[i] = worst;
  });
  for (std::size_t i = 0; i < N; ++i)
    if (one_sided[i].load(std::memory_order_relaxed)) d.reciprocity_error[i] = std::max(d.reciprocity_error[i], 1.0);
  return d;
}

}  // namespace radwalk
