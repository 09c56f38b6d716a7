#include "formfactor/form_factor_diagnostics.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/check.h"
#include "core/parallel.h"
#include "formfactor/transpose_slabs.h"

namespace radwalk {

namespace {
// The transposed slabs hold at least this many entries (8 MB), whatever the size of F.
constexpr std::size_t kMinSlabEntries = std::size_t(1) << 20;
}  // namespace

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

  // Closure and the largest binomial variance of each row.
  parallel_for(N, [&](std::size_t i) {
    double sum = 0, max_var = 0;
    for (std::int32_t k = outer[i]; k < outer[i + 1]; ++k) {
      sum += value[k];
      max_var = std::max(max_var, double(value[k]) * (1.0 - double(value[k])));
    }
    d.row_sum[i] = sum;
    if (!rays.empty()) d.row_std_error[i] = std::sqrt(max_var / rays[i]);
    if (!d.back_hit_fraction.empty()) d.back_hit_fraction[i] = double(back_hits[i]) / rays[i];
  });

  // Reciprocity of row i: row i of F (F_ij, j increasing) merged with row i of F^T (F_ji, j increasing), the
  // transpose built a slab of columns at a time (at most about one byte per non-zero besides F). A pair stored on
  // both sides contributes |g_ij - g_ji| / max(g_ij, g_ji), g_ij = A_i F_ij; a pair stored on one side only, with
  // a positive value, contributes 1 (to both rows: row i sees it in F or in F^T).
  TransposeSlabs slabs(*G, std::max<std::size_t>(std::size_t(G->nonZeros()) / 8, kMinSlabEntries));
  while (slabs.next()) {
    parallel_for(slabs.end() - slabs.begin(), [&](std::size_t c) {
      const std::size_t i = slabs.begin() + c;
      const TransposedRow t = slabs.row(i);
      double worst = 0;
      std::int32_t k = outer[i];
      std::size_t x = 0;
      while (k < outer[i + 1] || x < t.size) {
        if (x == t.size || (k < outer[i + 1] && inner[k] < t.entries[x].row)) {  // F_ij stored, F_ji absent
          if (area[i] * value[k] > 0) worst = std::max(worst, 1.0);
          ++k;
        } else if (k == outer[i + 1] || t.entries[x].row < inner[k]) {  // F_ji stored, F_ij absent
          if (area[std::size_t(t.entries[x].row)] * t.entries[x].value > 0) worst = std::max(worst, 1.0);
          ++x;
        } else {
          const double gij = area[i] * value[k], gji = area[std::size_t(t.entries[x].row)] * t.entries[x].value;
          const double m = std::max(gij, gji);
          if (m > 0) worst = std::max(worst, std::abs(gij - gji) / m);
          ++k;
          ++x;
        }
      }
      d.reciprocity_error[i] = worst;
    });
  }
  return d;
}

}  // namespace radwalk
