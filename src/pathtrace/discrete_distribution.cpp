#include "pathtrace/discrete_distribution.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"

namespace radwalk {

DiscreteDistribution::DiscreteDistribution(const std::vector<double>& weights) {
  for (std::size_t k = 0; k < weights.size(); ++k) {
    if (!(weights[k] >= 0) || !std::isfinite(weights[k]))
      throw InputError("discrete distribution: weight " + std::to_string(k) + " is " +
                       std::to_string(weights[k]) + " (must be finite and >= 0)");
    total_ += weights[k];
  }
  if (!(total_ > 0)) throw InputError("discrete distribution: no positive weight");
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

}  // namespace radwalk
