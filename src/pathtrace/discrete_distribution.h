#pragma once
// A discrete distribution over {0, ..., n-1} with probability p_k = w_k / sum(w), by inversion of the CDF.
// Sampling triplet: sample(u) -> k (and u re-used: (u - cdf_k) / p_k is again uniform), pmf(k), and the
// inverse interval [cdf_k, cdf_{k+1}) of the u that map to k.
#include <cstddef>
#include <utility>
#include <vector>

namespace radwalk {

class DiscreteDistribution {
 public:
  DiscreteDistribution() = default;
  // Non-negative weights; throws InputError when none is positive or one is negative or not finite.
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

}  // namespace radwalk
