#pragma once
// Sampling a discrete distribution over {0, ..., n-1} with probabilities p_k = w_k / sum_j w_j from non-negative
// weights w (at least one positive), in two ways, both from one uniform u in [0, 1):
//
// DiscreteDistribution: inversion of the CDF c_0 = 0, c_{k+1} = c_k + p_k (c_n = 1 exactly): sample(u) = the k
//   with c_k <= u < c_{k+1} (never an index of zero probability), by binary search in O(log n). The sampling
//   triplet: sample(u) -> k, with u re-used ((u - c_k) / p_k is again uniform on [0, 1)), pmf(k), and the
//   inverse interval [c_k, c_{k+1}) of the u that map to k.
//
// AliasTable (Walker 1977, Vose 1991): O(1) sampling after O(n) set-up. A table of n buckets; bucket b keeps
//   outcome primary[b] with probability threshold[b] and hands over to alias[b] otherwise. Drawing u:
//   b = floor(u n), f = u n - b, outcome = f < threshold[b] ? primary[b] : alias[b]. Built in double precision,
//   so pdf(outcome) is reproduced to about 1e-16 absolute. build_alias_buckets and sample_alias_buckets work on
//   bucket arrays with any outcome labels, for many tables in one array (walk/alias_table.h's RowAliasTables).
//
// Both throw InputError when a weight is negative or not finite, or none is positive.
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace radwalk {

class DiscreteDistribution {
 public:
  DiscreteDistribution() = default;
  explicit DiscreteDistribution(const std::vector<double>& weights);

  std::size_t size() const { return pmf_.size(); }
  double total() const { return total_; }
  // k with cdf_k <= u < cdf_{k+1}, never an index of zero probability. If remapped != nullptr, it gets
  // (u - cdf_k) / p_k in [0, 1).
  std::size_t sample(double u, double* remapped = nullptr) const;
  double pmf(std::size_t k) const { return pmf_[k]; }
  // The interval of u in [0, 1) that sample() maps to k.
  std::pair<double, double> inverse(std::size_t k) const { return {cdf_[k], cdf_[k + 1]}; }

 private:
  std::vector<double> pmf_;
  std::vector<double> cdf_;  // size n + 1, cdf_[0] = 0, cdf_[n] = 1
  double total_ = 0;
};

struct AliasBucket {
  double threshold = 1;  // probability of keeping `primary`
  std::int32_t primary = 0;
  std::int32_t alias = 0;
};

// Fills buckets[0..n) from probabilities q[0..n) summing to 1 (Vose's stable variant); `outcome[b]` labels
// entry b.
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

}  // namespace radwalk
