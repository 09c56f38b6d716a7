#pragma once
// The mean and the unbiased per-sample variance of m samples from their power sums, element by element (one
// value per channel, or per patch and channel):
//   mean = S1 / m,   var = max(0, (S2 - m mean^2) / (m - 1)),   S1 = sum x, S2 = sum x^2, m >= 2;
// the clamp at 0 absorbs rounding when every sample is (nearly) equal. The standard error of the mean is
// sqrt(var / m). For Eigen arrays (Rgb, PatchRgb).
#include <utility>

namespace radwalk {

template <class Array>
std::pair<Array, Array> mean_and_variance(const Array& sum, const Array& sum2, double m) {
  Array mean = sum / m;
  Array var = ((sum2 - m * mean * mean) / (m - 1.0)).max(0.0);
  return {std::move(mean), std::move(var)};
}

}  // namespace radwalk
