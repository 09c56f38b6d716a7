#pragma once
// Alias tables (Walker 1977, Vose 1991): O(1) sampling of a discrete distribution after O(n) set-up.
//
// A table of n buckets; bucket b keeps outcome primary[b] with probability threshold[b] and hands over to
// alias[b] otherwise. Drawing u in [0, 1): b = floor(u n), f = u n - b, outcome = f < threshold[b] ? primary[b]
// : alias[b]. Built in double precision, so pdf(outcome) is reproduced to about 1e-16 absolute.
//
// AliasTable: one distribution over {0..n-1}, proportional to non-negative weights.
// RowAliasTables: one table per row k of a sparse row-major F (the form factors), over the columns j of row k
// plus an escape outcome (the walk stop code kEscaped of transition_kernel.h):
//   P(j) = F_kj / n_k,  P(escape) = 1 - s_k / n_k,  s_k = sum_j F_kj,  n_k = max(s_k, 1) (the row scale).
// A row that sums below 1 (open scene) escapes with the deficit; a row that sums above 1 (rounding of a closed
// scene, or a biased F) is sampled in proportion and the caller multiplies its weight by n_k, which keeps
// estimators unbiased for the F given.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/types.h"
#include "formfactor/sparse_f.h"
#include "walk/transition_kernel.h"

namespace radwalk {

struct AliasBucket {
  double threshold = 1;  // probability of keeping `primary`
  std::int32_t primary = 0;
  std::int32_t alias = 0;
};

// Fills buckets[0..n) from probabilities q[0..n) summing to 1 (Vose's stable variant); `outcome[b]` labels
// entry b. Exposed for the two table kinds below.
void build_alias_buckets(const double* q, const std::int32_t* outcome, std::size_t n, AliasBucket* buckets);

inline std::int32_t sample_alias_buckets(const AliasBucket* buckets, std::size_t n, double u) {
  const double x = u * static_cast<double>(n);
  std::size_t b = static_cast<std::size_t>(x);
  if (b >= n) b = n - 1;
  const AliasBucket& bucket = buckets[b];
  return x - static_cast<double>(b) < bucket.threshold ? bucket.primary : bucket.alias;
}

class AliasTable {
 public:
  AliasTable() = default;
  // Throws InputError if a weight is negative or not finite, or all are zero.
  explicit AliasTable(const std::vector<double>& weights);
  std::size_t size() const { return pdf_.size(); }
  // Outcome for u in [0, 1).
  std::size_t sample(double u) const {
    return static_cast<std::size_t>(sample_alias_buckets(buckets_.data(), buckets_.size(), u));
  }
  // Probability of outcome i (= weight_i / sum of weights).
  double pdf(std::size_t i) const { return pdf_[i]; }

 private:
  std::vector<AliasBucket> buckets_;
  std::vector<double> pdf_;
};

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
