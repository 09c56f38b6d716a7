#include "formfactor/reciprocity.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "core/check.h"
#include "core/error.h"
#include "core/parallel.h"
#include "formfactor/transpose_slabs.h"

namespace radwalk {

namespace {
// The transposed slabs hold at least this many entries (8 MB), whatever the size of F.
constexpr std::size_t kMinSlabEntries = std::size_t(1) << 20;
}  // namespace

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
  const std::size_t nnz = std::size_t(F.nonZeros());
  const std::size_t slab_entries = std::max<std::size_t>(nnz / 8, kMinSlabEntries);

  // Pass 1: the length of each row of S = (G + G^T) / 2, G = diag(A) F: the union of the columns of row i of F
  // and of row i of F^T (both increasing, merged), counted a slab of columns at a time.
  SparseF out(static_cast<Eigen::Index>(N), static_cast<Eigen::Index>(N));
  std::int32_t* out_outer = out.outerIndexPtr();
  {
    std::vector<std::size_t> length(N, 0);
    TransposeSlabs slabs(F, slab_entries);
    while (slabs.next())
      parallel_for(slabs.end() - slabs.begin(), [&](std::size_t c) {
        const std::size_t i = slabs.begin() + c;
        const TransposedRow t = slabs.row(i);
        std::size_t n = 0;
        std::int32_t k = outer[i];
        std::size_t x = 0;
        while (k < outer[i + 1] || x < t.size) {
          const bool from_f = x == t.size || (k < outer[i + 1] && inner[k] <= t.entries[x].row);
          const bool from_t = k == outer[i + 1] || (x < t.size && t.entries[x].row <= inner[k]);
          k += from_f;
          x += from_t;
          ++n;
        }
        length[i] = n;
      });
    std::size_t total = 0;
    out_outer[0] = 0;
    for (std::size_t i = 0; i < N; ++i) {
      total += length[i];
      if (total > std::size_t(std::numeric_limits<std::int32_t>::max()))
        throw InputError(locate("enforce_reciprocity", 0, -1, "the symmetric form-factor matrix has more than 2^31-1 non-zeros"));
      out_outer[i + 1] = std::int32_t(total);
    }
    out.resizeNonZeros(Eigen::Index(total));
  }

  // Pass 2, row by row in order: S_ij = (A_i F_ij + A_j F_ji) / 2 (an absent side counts 0), F'_ij = S_ij / A_i,
  // the row rescaled when it sums above 1, the change measured entry by entry against F (summed in entry order),
  // stored as float.
  std::int32_t* out_inner = out.innerIndexPtr();
  float* out_value = out.valuePtr();
  ReciprocityChange change;
  double change_sum = 0;
  std::size_t entries = 0, at = 0;
  std::vector<double> row;          // F'_ij of the row, in column order
  std::vector<double> before;       // F_ij (0 where absent)
  TransposeSlabs slabs(F, slab_entries);
  while (slabs.next()) {
    for (std::size_t i = slabs.begin(); i < slabs.end(); ++i) {
      const TransposedRow t = slabs.row(i);
      row.clear();
      before.clear();
      const std::size_t row_start = at;
      std::int32_t k = outer[i];
      std::size_t x = 0;
      while (k < outer[i + 1] || x < t.size) {
        std::int32_t j;
        double s;
        if (x == t.size || (k < outer[i + 1] && inner[k] < t.entries[x].row)) {  // F_ij alone
          j = inner[k];
          s = area[i] * double(value[k]);
          before.push_back(double(value[k]));
          ++k;
        } else if (k == outer[i + 1] || t.entries[x].row < inner[k]) {  // F_ji alone
          j = t.entries[x].row;
          s = area[std::size_t(j)] * double(t.entries[x].value);
          before.push_back(0.0);
          ++x;
        } else {  // both
          j = inner[k];
          const double gij = area[i] * double(value[k]);
          s = gij + area[std::size_t(j)] * double(t.entries[x].value);
          before.push_back(double(value[k]));
          ++k;
          ++x;
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
    }
  }
  change.mean_relative_change = entries ? change_sum / double(entries) : 0.0;
  F = std::move(out);
  return change;
}

}  // namespace radwalk
