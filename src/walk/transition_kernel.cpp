#include "walk/transition_kernel.h"

#include <cmath>

#include "core/error.h"

namespace radwalk {

WalkTables make_walk_tables(const PatchRgb& rho, const PatchRgb& E, std::vector<double> p, std::vector<double> n,
                            std::vector<double> scored_stop) {
  const auto N = static_cast<std::size_t>(rho.rows());
  WalkTables t;
  t.p = std::move(p);
  t.n = std::move(n);
  t.scored_stop = std::move(scored_stop);
  t.E.resize(N);
  t.rho.resize(N);
  t.gather_weight.resize(N);
  t.absorb_score.resize(N);
  t.rho_over_p.resize(N);
  t.rho_over_1mp.resize(N);
  for (std::size_t k = 0; k < N; ++k) {
    const auto r = static_cast<Eigen::Index>(k);
    t.E[k] = E.row(r).transpose();
    t.rho[k] = rho.row(r).transpose();
    const double pk = t.p[k];
    t.gather_weight[k] = pk > 0 ? Rgb(t.rho[k] * (t.n[k] / pk)) : Rgb::Zero();
    t.rho_over_p[k] = pk > 0 ? Rgb(t.rho[k] / pk) : Rgb::Zero();
    t.rho_over_1mp[k] = pk < 1 ? Rgb(t.rho[k] / (1.0 - pk)) : Rgb::Zero();
    for (int c = 0; c < 3; ++c)
      t.absorb_score[k](c) = t.E[k](c) != 0 && t.scored_stop[k] > 0 ? t.E[k](c) / t.scored_stop[k] : 0.0;
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
