#pragma once
// Russian roulette with the weight correction (unbiased path termination, no depth cap): a path with throughput
// beta survives with probability q = min(1, max channel of beta), and a survivor's beta is divided by q, so
// E[beta after] = beta. One uniform from rng per call.
#include <algorithm>

#include "core/rng.h"
#include "core/types.h"

namespace radwalk {

// True when the path goes on (beta rescaled by 1 / q); false when it ends.
inline bool survive_russian_roulette(Rgb& beta, Rng& rng) {
  const double q = std::min(1.0, beta.maxCoeff());
  if (!(rng.uniform() < q)) return false;
  beta /= q;
  return true;
}

}  // namespace radwalk
