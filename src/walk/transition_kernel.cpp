#include "walk/transition_kernel.h"

#include <cmath>

#include "core/error.h"

namespace radwalk {

KernelTables make_kernel_tables(const PatchRgb& rho, const PatchRgb& E, std::vector<double> p, std::vector<double> n,
                                std::vector<double> s) {
  const auto N = static_cast<std::size_t>(rho.rows());
  KernelTables t;
  t.p = std::move(p);
  t.n = std::move(n);
  t.s = std::move(s);
  t.E.resize(N);
  t.rho.resize(N);
  for (std::size_t k = 0; k < N; ++k) {
    const auto r = static_cast<Eigen::Index>(k);
    t.E[k] = E.row(r).transpose();
    t.rho[k] = rho.row(r).transpose();
  }
  return t;
}

std::vector<double> survival_probabilities(const PatchRgb& rho, const std::string& mode, double constant) {
  const auto N = static_cast<std::size_t>(rho.rows());
  std::vector<double> p(N);
  if (mode == "analog") {
    // Mean over channels; exactly rho when the channels agree (the single-channel analog walk, weights 1).
    for (std::size_t k = 0; k < N; ++k) {
      const auto r = static_cast<Eigen::Index>(k);
      p[k] = rho.row(r).minCoeff() == rho.row(r).maxCoeff() ? rho(r, 0) : rho.row(r).mean();
    }
  } else if (mode == "max") {
    for (std::size_t k = 0; k < N; ++k) p[k] = rho.row(static_cast<Eigen::Index>(k)).maxCoeff();
  } else if (mode == "constant") {
    if (!(constant > 0 && constant <= 1))
      throw InputError("random walk: survival constant " + std::to_string(constant) + " is not in (0, 1]");
    p.assign(N, constant);
  } else {
    throw InputError("random walk: unknown survival mode '" + mode + "' (use analog, max or constant)");
  }
  for (double& x : p) x = std::min(x, 1.0);
  return p;
}

}  // namespace radwalk
