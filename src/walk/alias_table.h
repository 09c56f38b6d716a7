#pragma once
// Row alias tables: one alias table (core/discrete_distribution.h) per row k of a sparse row-major F (the form
// factors), over the columns j of row k plus an escape outcome (the walk stop code kEscaped of transition_kernel.h):
//   P(j) = F_kj / n_k,  P(escape) = 1 - s_k / n_k,  s_k = sum_j F_kj,  n_k = max(s_k, 1) (the row scale).
// A row that sums below 1 (open scene) escapes with the deficit; a row that sums above 1 (rounding of a closed
// scene, or a biased F) is sampled in proportion and the caller multiplies its weight by n_k, which keeps
// estimators unbiased for the F given.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/discrete_distribution.h"
#include "core/types.h"
#include "formfactor/sparse_f.h"
#include "walk/transition_kernel.h"

namespace radwalk {


class RowAliasTables {
 public:
  RowAliasTables() = default;
  // Throws InputError if F is not square or has a negative or non-finite entry.
  explicit RowAliasTables(const SparseF& F);
  std::size_t rows() const { return row_sum_.size(); }
  // Column j of row k with probability F_kj / n_k, or kEscaped with probability 1 - s_k / n_k.
  PatchIndex sample(std::size_t k, double u) const {
    return sample_alias_buckets(buckets_.data() + begin_[k], begin_[k + 1] - begin_[k], u);
  }
  // Probability that sample(k, .) returns j (j = kEscaped: the escape probability), read back from the
  // buckets of row k (O(entries of row k)): a check that the table encodes F_kj / n_k.
  double pdf(std::size_t k, PatchIndex j) const;
  double row_sum(std::size_t k) const { return row_sum_[k]; }  // s_k
  double row_scale(std::size_t k) const { return row_sum_[k] > 1 ? row_sum_[k] : 1.0; }  // n_k
  std::size_t memory_bytes() const;

 private:
  std::vector<std::size_t> begin_;  // buckets of row k: [begin_[k], begin_[k+1])
  std::vector<AliasBucket> buckets_;
  std::vector<double> row_sum_;
};

}  // namespace radwalk
