#include "walk/shoot_estimators.h"

#include <string>

#include "core/check.h"
#include "core/error.h"

namespace radwalk {

ShootSource make_shoot_source(const PatchRgb& E, const Eigen::VectorXd& area) {
  RADWALK_CHECK_EQ(E.rows(), area.size());  // one emission row per area
  const auto N = static_cast<std::size_t>(area.size());
  // Phi_i = A_i sum_c E_ic.
  std::vector<double> Phi(N);
  ShootSource s;
  for (std::size_t i = 0; i < N; ++i) {
    const auto r = static_cast<Eigen::Index>(i);
    if (!(area(r) >= 0) || !(E.row(r).minCoeff() >= 0))
      throw InputError("shooting: patch " + std::to_string(i) + " has a negative area or emission");
    Phi[i] = area(r) * E.row(r).sum();
    s.power += Phi[i];
  }
  s.W0.assign(N, Rgb::Zero());
  if (!(s.power > 0)) return s;
  s.birth = AliasTable(Phi);
  // W0 = A_i E_i / pi_i = Phi E_i / sum_c E_ic.
  for (std::size_t i = 0; i < N; ++i)
    if (Phi[i] > 0) s.W0[i] = E.row(static_cast<Eigen::Index>(i)).transpose() * (s.power / E.row(static_cast<Eigen::Index>(i)).sum());
  return s;
}

ShootWeights::ShootWeights(const KernelTables& kernel) : survivor(kernel.p.size()) {
  for (std::size_t k = 0; k < survivor.size(); ++k) {
    const double pk = kernel.p[k];
    survivor[k] = pk > 0 ? Rgb(kernel.rho[k] / pk) : Rgb::Zero();
  }
}

ShootAbsorption::Tables::Tables(const KernelTables& kernel) : ShootWeights(kernel), absorbed(kernel.p.size()) {
  for (std::size_t k = 0; k < absorbed.size(); ++k) {
    const double pk = kernel.p[k];
    absorbed[k] = pk < 1 ? Rgb(kernel.rho[k] / (1.0 - pk)) : Rgb::Zero();
  }
}

}  // namespace radwalk
