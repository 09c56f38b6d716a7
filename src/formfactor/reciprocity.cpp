#include "formfactor/reciprocity.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "core/check.h"
#include "core/error.h"
#include "core/parallel.h"

namespace radwalk {

ReciprocityChange enforce_reciprocity(SparseF& F, const std::vector<double>& area) {
  const std::size_t N = std::size_t(F.rows());
  RADWALK_CHECK_EQ(F.cols(), F.rows());
  RADWALK_CHECK_EQ(area.size(), N);
  for (std::size_t i = 0; i < N; ++i)
    if (!(std::isfinite(area[i]) && area[i] > 0))
      throw InputError(locate("enforce_reciprocity", 0, long(i), "area " + std::to_string(area[i]) + " is not > 0"));

  if (!F.isCompressed()) F.makeCompressed();
  const std::int32_t* outer = F.outerIndexPtr();
  const std::int32_t* inner = F.innerIndexPtr();
  const float* value = F.valuePtr();
  // F_ji of row j (columns increase), or nullptr when absent.
  const auto entry = [&](std::int32_t j, std::int32_t i) -> const float* {
    const std::int32_t* end = inner + outer[j + 1];
    const std::int32_t* at = std::lower_bound(inner + outer[j], end, i);
    return at != end && *at == i ? value + (at - inner) : nullptr;
  };

  // Step 1: the one-sided entries, F_ji present and F_ij absent, as extra columns j of row i (each row's in
  // increasing j): S = (G + G^T) / 2, G = diag(A) F, has the pattern of F and F^T, and these are what F^T adds.
  // Memory: 1 byte per non-zero of F and 4 per extra entry, not the transposes of G (no copy of F).
  const std::size_t nnz = std::size_t(F.nonZeros());
  std::vector<std::uint8_t> one_sided(nnz);
  parallel_for(N, [&](std::size_t j) {
    for (std::int32_t k = outer[j]; k < outer[j + 1]; ++k)
      one_sided[std::size_t(k)] = entry(inner[k], std::int32_t(j)) == nullptr;
  });
  std::vector<std::size_t> extra_start(N + 1, 0);
  for (std::size_t j = 0; j < N; ++j)
    for (std::int32_t k = outer[j]; k < outer[j + 1]; ++k) extra_start[std::size_t(inner[k]) + 1] += one_sided[std::size_t(k)];
  for (std::size_t i = 0; i < N; ++i) extra_start[i + 1] += extra_start[i];
  const std::size_t extras = extra_start[N];
  if (nnz + extras > std::size_t(std::numeric_limits<std::int32_t>::max()))
    throw InputError(locate("enforce_reciprocity", 0, -1, "the symmetric form-factor matrix has more than 2^31-1 non-zeros"));
  std::vector<std::int32_t> extra_col(extras);
  {
    std::vector<std::size_t> cursor(extra_start.begin(), extra_start.end() - 1);
    for (std::size_t j = 0; j < N; ++j)
      for (std::int32_t k = outer[j]; k < outer[j + 1]; ++k)
        if (one_sided[std::size_t(k)]) extra_col[cursor[std::size_t(inner[k])]++] = std::int32_t(j);
  }
  one_sided = {};

  // Step 2, row by row: S_ij = (A_i F_ij + A_j F_ji) / 2 (an absent side counts 0), F'_ij = S_ij / A_i, the row
  // rescaled when it sums above 1, the change measured entry by entry against F, stored as float.
  SparseF out(static_cast<Eigen::Index>(N), static_cast<Eigen::Index>(N));
  out.resizeNonZeros(Eigen::Index(nnz + extras));
  std::int32_t* out_outer = out.outerIndexPtr();
  std::int32_t* out_inner = out.innerIndexPtr();
  float* out_value = out.valuePtr();
  ReciprocityChange change;
  double change_sum = 0;
  std::size_t entries = 0, at = 0;
  std::vector<double> row;          // F'_ij of the row, in column order
  std::vector<double> before;       // F_ij (0 where absent)
  out_outer[0] = 0;
  for (std::size_t i = 0; i < N; ++i) {
    row.clear();
    before.clear();
    const std::size_t row_start = at;
    std::int32_t k = outer[i];
    std::size_t x = extra_start[i];
    while (k < outer[i + 1] || x < extra_start[i + 1]) {
      std::int32_t j;
      double s;
      if (x == extra_start[i + 1] || (k < outer[i + 1] && inner[k] < extra_col[x])) {
        j = inner[k];
        const double gij = area[i] * double(value[k]);
        const float* fji = entry(j, std::int32_t(i));
        s = fji ? gij + area[std::size_t(j)] * double(*fji) : gij;
        before.push_back(double(value[k]));
        ++k;
      } else {
        j = extra_col[x++];
        s = area[std::size_t(j)] * double(*entry(j, std::int32_t(i)));
        before.push_back(0.0);
      }
      out_inner[at++] = j;
      row.push_back(0.5 * s);
    }
    double sum = 0;
    for (double& v : row) sum += (v /= area[i]);
    if (sum > 1.0) {
      for (double& v : row) v /= sum;
      ++change.rows_rescaled;
      change.max_row_excess = std::max(change.max_row_excess, sum - 1.0);
    }
    for (std::size_t q = 0; q < row.size(); ++q) {
      const double m = std::max(before[q], row[q]);
      const double rel = m > 0 ? std::abs(row[q] - before[q]) / m : 0.0;
      change.max_relative_change = std::max(change.max_relative_change, rel);
      change_sum += rel;
      ++entries;
      out_value[row_start + q] = static_cast<float>(row[q]);
    }
    out_outer[i + 1] = std::int32_t(at);
  }
  change.mean_relative_change = entries ? change_sum / double(entries) : 0.0;
  F = std::move(out);
  return change;
}

}  // namespace radwalk
