#include "walk/gather_estimators.h"

namespace radwalk {

GatherWeights::GatherWeights(const KernelTables& kernel) : w(kernel.p.size()) {
  for (std::size_t k = 0; k < w.size(); ++k) {
    const double pk = kernel.p[k];
    w[k] = pk > 0 ? Rgb(kernel.rho[k] * (kernel.n[k] / pk)) : Rgb::Zero();
  }
}

GatherAbsorption::Tables::Tables(const KernelTables& kernel)
    : GatherWeights(kernel), score(kernel.p.size()), escape_scores(kernel.row_sums_known()) {
  for (std::size_t k = 0; k < score.size(); ++k) {
    // Probability of a scored stop at k: every stop (q_k = 1 - p_k s_k / n_k) or only the roulette (1 - p_k).
    const double q = escape_scores ? 1.0 - kernel.p[k] * kernel.s[k] / kernel.n[k] : 1.0 - kernel.p[k];
    for (int c = 0; c < 3; ++c) score[k](c) = kernel.E[k](c) != 0 && q > 0 ? kernel.E[k](c) / q : 0.0;
  }
}

}  // namespace radwalk
