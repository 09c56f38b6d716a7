#include "support/statistics.h"

#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <limits>

namespace radwalk {

double sidak(double alpha, std::size_t m) {
  if (m <= 1) return alpha;
  return -std::expm1(std::log1p(-alpha) / static_cast<double>(m));
}

double z_critical(double alpha) {
  return boost::math::quantile(boost::math::complement(boost::math::normal(), alpha / 2.0));
}

double chi_square_upper_tail(double x, double dof) {
  if (x <= 0) return 1.0;
  return boost::math::cdf(boost::math::complement(boost::math::chi_squared(dof), x));
}

double chi_square_gof_p_value(const std::vector<double>& observed, const std::vector<double>& expected) {
  double chi2 = 0, pooled_obs = 0, pooled_exp = 0;
  std::size_t bins = 0;
  for (std::size_t k = 0; k < observed.size(); ++k) {
    if (expected[k] < 5) {
      pooled_obs += observed[k];
      pooled_exp += expected[k];
      continue;
    }
    const double d = observed[k] - expected[k];
    chi2 += d * d / expected[k];
    ++bins;
  }
  if (pooled_exp > 0) {
    const double d = pooled_obs - pooled_exp;
    chi2 += d * d / pooled_exp;
    ++bins;
  }
  if (bins < 2) return 1.0;
  return chi_square_upper_tail(chi2, static_cast<double>(bins - 1));
}

double variance_z_score(double s2, double var_true, double mu4, std::size_t n) {
  const double nn = static_cast<double>(n);
  const double var_s2 = std::max((mu4 - var_true * var_true * (nn - 3.0) / (nn - 1.0)) / nn, 0.0);
  if (var_s2 <= 0) return s2 == var_true ? 0.0 : std::numeric_limits<double>::infinity();
  return (s2 - var_true) / std::sqrt(var_s2);
}

}  // namespace radwalk
