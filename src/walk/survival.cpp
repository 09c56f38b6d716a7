#include "walk/survival.h"

#include <algorithm>
#include <string>

#include "core/error.h"
#include "walk/named_choice.h"

namespace radwalk {

SurvivalRule parse_survival_rule(std::string_view name) {
  return find_choice(kSurvivalRules, name, "survival mode").value;
}

void check_survival(const Survival& survival) {
  if (survival.rule == SurvivalRule::constant && !(survival.constant > 0 && survival.constant < 1))
    throw InputError("random walk: survival constant " + number_text(survival.constant) + " is not in (0, 1)");
}

std::vector<double> survival_probabilities(const PatchRgb& rho, const Survival& survival) {
  check_survival(survival);
  const auto N = static_cast<std::size_t>(rho.rows());
  std::vector<double> p(N);
  switch (survival.rule) {
    case SurvivalRule::analog:
      // Mean over channels; exactly rho when the channels agree (the single-channel analog walk, weights 1).
      for (std::size_t k = 0; k < N; ++k) {
        const auto r = static_cast<Eigen::Index>(k);
        p[k] = rho.row(r).minCoeff() == rho.row(r).maxCoeff() ? rho(r, 0) : rho.row(r).mean();
      }
      break;
    case SurvivalRule::max:
      for (std::size_t k = 0; k < N; ++k) p[k] = rho.row(static_cast<Eigen::Index>(k)).maxCoeff();
      break;
    case SurvivalRule::constant:
      p.assign(N, survival.constant);
      break;
  }
  for (double& x : p) x = std::min(x, 1.0);
  return p;
}

void check_survival_probabilities(const std::vector<double>& p, const PatchRgb& rho, SurvivalRule rule) {
  const std::string mode(survival_name(rule));
  for (std::size_t k = 0; k < p.size(); ++k) {
    const auto r = static_cast<Eigen::Index>(k);
    if (!(p[k] < 1))
      throw InputError("random walk: survival probability p = " + number_text(p[k]) + " at patch " +
                       std::to_string(k) + " (survival '" + mode + "') is not below 1: walks might never end");
    if (!(p[k] > 0) && rho.row(r).maxCoeff() > 0)
      throw InputError("random walk: survival probability 0 at patch " + std::to_string(k) +
                       " whose reflectance is positive (survival '" + mode + "') would bias the estimate");
  }
}

}  // namespace radwalk
