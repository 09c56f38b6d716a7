#include "solve/group_mean_error.h"

#include <cmath>

#include "core/check.h"
#include "core/moments.h"
#include "solve/discretisation_error.h"

namespace radwalk {

std::vector<GroupMeanError> group_mean_errors(const PatchSet& patches, const PatchGrouping& grouping,
                                              const RadiosityProblem& p, const PatchRgb& B, const PatchRgb& B_se,
                                              const PatchRgb& d, const PatchRgb& d_sd, double keep_shares_above) {
  const std::size_t N = patches.size();
  RADWALK_CHECK_EQ(grouping.group.size(), N);
  RADWALK_CHECK_EQ(B.rows(), static_cast<Eigen::Index>(N));
  const bool has_se = B_se.rows() == B.rows();
  // Sums of B scaled before they are formed (core/moments.h): B near the largest double.
  const double s = moment_scale(B.size() > 0 ? std::max(B.abs().maxCoeff(), has_se ? B_se.maxCoeff() : 0.0) : 0.0);
  std::vector<GroupMeanError> out(grouping.names.size());
  std::vector<double> M(out.size(), 0.0), se(out.size(), 0.0);
  for (std::size_t g = 0; g < out.size(); ++g) out[g].name = grouping.names[g];
  for (std::size_t i = 0; i < N; ++i) {
    if (!(patches.E[i].maxCoeff() <= 0 && patches.rho[i].maxCoeff() > 0)) continue;
    const auto g = static_cast<std::size_t>(grouping.group[i]);
    const auto row = static_cast<Eigen::Index>(i);
    out[g].counted = true;
    out[g].area += patches.area[i];
    M[g] += patches.area[i] * (B.row(row) / s).sum();
    if (has_se) se[g] += patches.area[i] * (B_se.row(row) / s).sum();
  }
  for (std::size_t g = 0; g < out.size(); ++g) {
    GroupMeanError& x = out[g];
    if (!x.counted) continue;
    x.mean = s * M[g] / (3 * x.area);
    if (!(M[g] > 0)) continue;  // a black group: no relative error
    Eigen::VectorXd W = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(N));
    for (std::size_t i = 0; i < N; ++i)
      if (grouping.group[i] == static_cast<std::int32_t>(g) && patches.E[i].maxCoeff() <= 0 &&
          patches.rho[i].maxCoeff() > 0)
        W[static_cast<Eigen::Index>(i)] = patches.area[i];
    const MeasurementDiscretisationError m = measurement_discretisation_error(p, d, d_sd, W);
    const double eps = (m.estimate / s).sum(), sd = (m.estimate_sd / s).sum();
    x.estimate = eps / M[g];
    x.discretisation = std::hypot(eps, sd) / M[g];
    x.statistical = se[g] / M[g];
    x.total = std::hypot(x.discretisation, x.statistical);
    if (x.total > keep_shares_above) {
      x.share.resize(N);
      for (std::size_t j = 0; j < N; ++j) x.share[j] = std::abs((m.share.row(Eigen::Index(j)) / s).sum()) / M[g];
    }
  }
  return out;
}

}  // namespace radwalk
