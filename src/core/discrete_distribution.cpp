#include "core/discrete_distribution.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"

namespace radwalk {
namespace {

// sum_k w_k, after checking that every weight is finite and >= 0 and one is positive.
double weight_total(const std::vector<double>& weights) {
  double total = 0;
  for (std::size_t k = 0; k < weights.size(); ++k) {
    if (!(weights[k] >= 0) || !std::isfinite(weights[k]))
      throw InputError("discrete distribution: weight " + std::to_string(k) + " is " +
                       std::to_string(weights[k]) + " (must be finite and >= 0)");
    total += weights[k];
  }
  if (!(total > 0)) throw InputError("discrete distribution: no positive weight");
  return total;
}

}  // namespace

DiscreteDistribution::DiscreteDistribution(const std::vector<double>& weights) : total_(weight_total(weights)) {
  pmf_.resize(weights.size());
  cdf_.assign(weights.size() + 1, 0.0);
  // Running sum, then normalise; the last entry is exactly 1.
  for (std::size_t k = 0; k < weights.size(); ++k) {
    pmf_[k] = weights[k] / total_;
    cdf_[k + 1] = cdf_[k] + weights[k];
  }
  for (auto& c : cdf_) c /= total_;
  cdf_.back() = 1.0;
}

std::size_t DiscreteDistribution::sample(double u, double* remapped) const {
  // First k with cdf_{k+1} > u; skips zero-probability entries because their interval is empty.
  auto it = std::upper_bound(cdf_.begin() + 1, cdf_.end(), u);
  if (it == cdf_.end()) --it;
  std::size_t k = static_cast<std::size_t>(it - cdf_.begin()) - 1;
  while (pmf_[k] == 0 && k > 0) --k;  // only reachable through rounding at u -> 1
  if (remapped) *remapped = std::clamp((u - cdf_[k]) / (cdf_[k + 1] - cdf_[k]), 0.0, 0x1.fffffffffffffp-1);
  return k;
}

void build_alias_buckets(const double* q, const std::int32_t* outcome, std::size_t n, AliasBucket* buckets) {
  // Scaled probabilities n q_b; "small" buckets (< 1) borrow from "large" ones (>= 1).
  std::vector<double> scaled(n);
  std::vector<std::size_t> small, large;
  small.reserve(n);
  large.reserve(n);
  for (std::size_t b = 0; b < n; ++b) {
    scaled[b] = q[b] * static_cast<double>(n);
    (scaled[b] < 1.0 ? small : large).push_back(b);
  }
  // Pair each small bucket with a large donor; the donor's remainder goes back to the matching list.
  while (!small.empty() && !large.empty()) {
    const std::size_t s = small.back(), l = large.back();
    small.pop_back();
    large.pop_back();
    buckets[s] = {scaled[s], outcome[s], outcome[l]};
    scaled[l] = (scaled[l] + scaled[s]) - 1.0;
    (scaled[l] < 1.0 ? small : large).push_back(l);
  }
  // Leftovers are full buckets up to rounding.
  for (std::size_t b : large) buckets[b] = {1.0, outcome[b], outcome[b]};
  for (std::size_t b : small) buckets[b] = {1.0, outcome[b], outcome[b]};
}

AliasTable::AliasTable(const std::vector<double>& weights) {
  const double total = weight_total(weights);
  const std::size_t n = weights.size();
  pdf_.resize(n);
  std::vector<std::int32_t> outcome(n);
  for (std::size_t i = 0; i < n; ++i) {
    pdf_[i] = weights[i] / total;
    outcome[i] = static_cast<std::int32_t>(i);
  }
  buckets_.resize(n);
  build_alias_buckets(pdf_.data(), outcome.data(), n, buckets_.data());
}

}  // namespace radwalk
