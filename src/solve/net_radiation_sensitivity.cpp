#include "solve/net_radiation_sensitivity.h"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <string>

#include "core/check.h"
#include "core/error.h"

namespace radwalk {

NetRadiationSensitivity net_radiation_sensitivity(const NetRadiationInput& input, const SparseF& F,
                                                  const NetRadiationResult& r, const std::vector<std::int32_t>& group,
                                                  int groups, const std::vector<int>& responses) {
  const std::size_t n = input.area.size();
  RADWALK_CHECK_EQ(std::size_t(F.rows()), n);
  RADWALK_CHECK_EQ(group.size(), n);
  RADWALK_CHECK_EQ(r.J.size(), n);
  const NetRadiationCoefficients c = net_radiation_coefficients(input);
  // A^T = I - F^T diag(rho), column-major for the solver.
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(std::size_t(F.nonZeros()) + n);
  for (std::size_t i = 0; i < n; ++i) {
    triplets.emplace_back(int(i), int(i), 1.0);
    for (SparseF::InnerIterator it(F, Eigen::Index(i)); it; ++it)
      triplets.emplace_back(int(it.col()), int(i), -c.rho[i] * double(it.value()));
  }
  Eigen::SparseMatrix<double> At(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  At.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::BiCGSTAB<Eigen::SparseMatrix<double>> solver;
  solver.setTolerance(1e-13);
  solver.setMaxIterations(std::max<Eigen::Index>(1000, 10 * Eigen::Index(n)));
  solver.compute(At);

  // Per known-temperature patch k: the factors multiplying (A_k 1[k in G] - psi_k).
  std::vector<double> eps_factor(n, 0.0), T_factor(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    const SurfaceCondition& s = input.surface[k];
    if (!s.temperature_given) continue;
    const double T = s.temperature;
    eps_factor[k] = kStefanBoltzmann * T * T * T * T - r.G[k];
    T_factor[k] = 4 * s.emissivity * kStefanBoltzmann * T * T * T;
  }
  NetRadiationSensitivity out;
  out.dQ_deps = Eigen::MatrixXd::Zero(Eigen::Index(responses.size()), groups);
  out.dQ_dT = Eigen::MatrixXd::Zero(Eigen::Index(responses.size()), groups);
  for (std::size_t k = 0; k < responses.size(); ++k) {
    const int G = responses[k];
    RADWALK_CHECK(G >= 0 && G < groups);
    // g = F^T a.
    Eigen::VectorXd g = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n));
    for (std::size_t i = 0; i < n; ++i) {
      if (group[i] != G || !input.surface[i].temperature_given) continue;
      const double a = input.area[i] * input.surface[i].emissivity;
      for (SparseF::InnerIterator it(F, Eigen::Index(i)); it; ++it) g(it.col()) += a * double(it.value());
    }
    const Eigen::VectorXd psi = solver.solve(g);
    out.iterations.push_back(long(solver.iterations()));
    out.residual.push_back(solver.error());
    if (!(solver.error() <= 1e-9))
      throw InputError("sensitivities: the adjoint system of response group " + std::to_string(G) +
                       " was not solved (BiCGSTAB relative residual " + std::to_string(solver.error()) + " after " +
                       std::to_string(solver.iterations()) + " iterations)");
    for (std::size_t i = 0; i < n; ++i) {
      if (!input.surface[i].temperature_given) continue;
      const double weight = (group[i] == G ? input.area[i] : 0.0) - psi(Eigen::Index(i));
      out.dQ_deps(Eigen::Index(k), group[i]) += eps_factor[i] * weight;
      out.dQ_dT(Eigen::Index(k), group[i]) += T_factor[i] * weight;
    }
  }
  return out;
}

}  // namespace radwalk
