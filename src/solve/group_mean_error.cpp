#include "solve/group_mean_error.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"
#include "core/moments.h"
#include "solve/discretisation_error.h"
#include "solve/form_factor_error.h"

namespace radwalk {

std::vector<GroupMeanError> group_mean_errors(const PatchSet& patches, const PatchGrouping& grouping,
                                              const RadiosityProblem& p, const PatchRgb& B, const PatchRgb& B_se,
                                              const PatchRgb& d, const PatchRgb& d_sd, double keep_shares_above,
                                              const GroupNoiseModel& noise) {
  const std::size_t N = patches.size();
  const auto n = static_cast<Eigen::Index>(N);
  RADWALK_CHECK_EQ(grouping.group.size(), N);
  RADWALK_CHECK_EQ(B.rows(), n);
  const bool has_se = B_se.rows() == n;
  const bool first_order = n > 0 && noise.gather_standard_error.rows() == n;
  const bool has_own = first_order && noise.solver_standard_error.rows() == n &&
                       noise.solver_standard_error.maxCoeff() > 0;
  // Sums of B scaled before they are formed (core/moments.h): B near the largest double.
  double largest = B.size() > 0 ? B.abs().maxCoeff() : 0.0;
  if (has_se) largest = std::max(largest, B_se.maxCoeff());
  if (first_order) largest = std::max(largest, noise.gather_standard_error.maxCoeff());
  if (has_own) largest = std::max(largest, noise.solver_standard_error.maxCoeff());
  const double s = moment_scale(largest);
  // The row noise Psi sees: rho_jc sqrt(V_jc) / s.
  const PatchRgb rho_g = first_order ? PatchRgb(p.rho * (noise.gather_standard_error / s)) : PatchRgb();
  std::vector<GroupMeanError> out(grouping.names.size());
  std::vector<double> M(out.size(), 0.0), se(out.size(), 0.0), own(out.size(), 0.0);
  for (std::size_t g = 0; g < out.size(); ++g) out[g].name = grouping.names[g];
  for (std::size_t i = 0; i < N; ++i) {
    if (!(patches.E[i].maxCoeff() <= 0 && patches.rho[i].maxCoeff() > 0)) continue;
    const auto g = static_cast<std::size_t>(grouping.group[i]);
    const auto row = static_cast<Eigen::Index>(i);
    out[g].counted = true;
    out[g].area += patches.area[i];
    M[g] += patches.area[i] * (B.row(row) / s).sum();
    if (has_se) se[g] += patches.area[i] * (B_se.row(row) / s).sum();
    if (has_own) own[g] += patches.area[i] * (noise.solver_standard_error.row(row) / s).sum();
  }
  double largest_area = 0;
  for (std::size_t i = 0; i < N; ++i) largest_area = std::max(largest_area, patches.area[i]);
  const double r = moment_scale(largest_area);
  for (std::size_t g = 0; g < out.size(); ++g) {
    GroupMeanError& x = out[g];
    if (!x.counted) continue;
    x.mean = s * M[g] / (3 * x.area);
    if (!(M[g] > 0)) continue;  // a black group: no relative error
    // The adjoint of M_g, shared by both parts: Psi_g = (I - H)^{-T} (A 1_g) / r.
    Eigen::VectorXd W = Eigen::VectorXd::Zero(n);
    for (std::size_t i = 0; i < N; ++i)
      if (grouping.group[i] == static_cast<std::int32_t>(g) && patches.E[i].maxCoeff() <= 0 &&
          patches.rho[i].maxCoeff() > 0)
        W[static_cast<Eigen::Index>(i)] = patches.area[i] / r;
    long sweeps = 0;
    const PatchRgb psi = adjoint_weights(p, W, sweeps);
    const MeasurementDiscretisationError m = measurement_discretisation_error(psi, r, d, d_sd);
    const double eps = (m.estimate / s).sum(), sd = (m.estimate_sd / s).sum();
    x.estimate = eps / M[g];
    x.discretisation = std::hypot(eps, sd) / M[g];
    x.statistical_bound = se[g] / M[g];
    if (first_order) {
      // sum_c sqrt(Var_F(M_gc)) (channels as if fully correlated), then the solver's own part added in variance.
      const double from_F = (psi * rho_g).square().colwise().sum().sqrt().sum() * r;
      x.statistical = std::hypot(from_F, own[g]) / M[g];
      x.statistical_kind = has_own ? "first-order+walk-bound" : "first-order";
    } else {
      x.statistical = x.statistical_bound;
      x.statistical_kind = "bound";
    }
    x.total = std::hypot(x.discretisation, x.statistical);
    if (x.total > keep_shares_above) {
      x.share.resize(N);
      for (std::size_t j = 0; j < N; ++j) x.share[j] = std::abs((m.share.row(Eigen::Index(j)) / s).sum()) / M[g];
    }
  }
  return out;
}

}  // namespace radwalk
