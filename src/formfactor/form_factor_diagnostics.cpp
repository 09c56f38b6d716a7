#include "formfactor/form_factor_diagnostics.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/check.h"
#include "core/parallel.h"

namespace radwalk {

FormFactorDiagnostics diagnose_form_factors(const SparseF& F, const std::vector<double>& area,
                                            const std::vector<std::uint32_t>& rays,
                                            const std::vector<std::uint32_t>& back_hits) {
  const std::size_t N = std::size_t(F.rows());
  RADWALK_CHECK_EQ(F.cols(), F.rows());
  RADWALK_CHECK_EQ(area.size(), N);
  if (!rays.empty()) RADWALK_CHECK_EQ(rays.size(), N);
  if (!back_hits.empty()) RADWALK_CHECK_EQ(back_hits.size(), N);

  FormFactorDiagnostics d;
  d.row_sum.assign(N, 0.0);
  d.reciprocity_error.assign(N, 0.0);
  if (!rays.empty()) d.row_std_error.assign(N, 0.0);
  if (!rays.empty() && !back_hits.empty()) d.back_hit_fraction.assign(N, 0.0);
  const SparseF Ft = F.transpose();  // row i of Ft holds F_ji

  parallel_for(N, [&](std::size_t i) {
    // Closure and the largest binomial variance of the row.
    double sum = 0, max_var = 0;
    for (SparseF::InnerIterator it(F, Eigen::Index(i)); it; ++it) {
      sum += it.value();
      max_var = std::max(max_var, double(it.value()) * (1.0 - double(it.value())));
    }
    d.row_sum[i] = sum;
    if (!rays.empty()) d.row_std_error[i] = std::sqrt(max_var / rays[i]);
    if (!d.back_hit_fraction.empty()) d.back_hit_fraction[i] = double(back_hits[i]) / rays[i];

    // Reciprocity: merge row i of F (F_ij) with row i of F^T (F_ji), both sorted by j.
    double worst = 0;
    SparseF::InnerIterator a(F, Eigen::Index(i)), b(Ft, Eigen::Index(i));
    while (a || b) {
      double gij = 0, gji = 0;
      if (a && (!b || a.index() <= b.index())) {
        const auto j = a.index();
        gij = area[i] * a.value();
        if (b && b.index() == j) {
          gji = area[j] * b.value();
          ++b;
        }
        ++a;
      } else {
        gji = area[b.index()] * b.value();
        ++b;
      }
      const double m = std::max(gij, gji);
      if (m > 0) worst = std::max(worst, std::abs(gij - gji) / m);
    }
    d.reciprocity_error[i] = worst;
  });
  return d;
}

}  // namespace radwalk
