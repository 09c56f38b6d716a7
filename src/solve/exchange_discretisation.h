#pragma once
// The heat exchange's discretisation error of J (solve/discretisation_error.h on the net-radiation problem) and
// what follows for q, Q and T, with the totals sqrt(se^2 + disc^2) (docs/heat-exchange.md, "Errors").
#include <cstdint>
#include <string>
#include <vector>

#include "patch/patch_set.h"
#include "solve/net_radiation.h"
#include "solve/problem.h"

namespace radwalk {

struct ExchangeDiscretisation {
  std::vector<double> J, q, Q, T;  // one-standard-deviation equivalents, W/m^2, W/m^2, W, K
  double seconds = 0;
  int points = 0, directions = 0;  // per patch, per point (solve/discretisation_error.h)
  long rays = 0, sweeps = 0;
};

// problem: the solved net-radiation problem (channel 0 the positive source part, channel 1 the negative one);
// B: its solution; r: the results. Channel errors e_c (signed) and Var(e_c) combine as
//   e_J = e_0 - e_1,   J_disc = sqrt(e_J^2 + (sd_0 + sd_1)^2)        (sd_c = sqrt(Var(e_c)); correlation unknown)
// and then, as the statistical errors (docs/theory/net_radiation.md):
//   known T, eps < 1: q_disc = eps/(1 - eps) J_disc;  eps = 1: q_disc = sum_j F_ij J_disc_j (J's part only);
//   known q: T_disc = J_disc / (4 sigma T^3);  Q_disc = A q_disc.
// directions L >= 1.
ExchangeDiscretisation exchange_discretisation(const PatchSet& patches, const RadiosityProblem& problem,
                                               const PatchRgb& B, const NetRadiationInput& input,
                                               const NetRadiationResult& r, int directions, std::uint64_t seed);

}  // namespace radwalk
