#pragma once
// A synthetic radiosity problem with the row structure of Monte Carlo form factors, for benchmarks and tests
// where no mesh is needed. Row i holds the landing counts of `rays` rays from patch i divided by `rays`:
// a ray escapes with probability 0.1 (an open side, as in the Cornell box), lands near i in patch order with
// probability 0.45 (neighbours on the same wall: index i +- N/50), or anywhere else (never on i itself). So rows
// sum to about 0.9, hold at most `rays` non-zeros, and F is not reciprocal. Materials follow the Cornell box
// conversion of Cardenas and McGuire (white 0.725 0.71 0.68, red 0.63 0.065 0.05, green 0.14 0.45 0.091) in
// blocks of patches; 1 % of the patches emit E = pi * (17, 12, 4) with rho 0.78. Areas 1. Deterministic in seed.
#include <cstdint>

#include "solve/problem.h"

namespace radwalk {

RadiosityProblem make_synthetic_problem(long patches, int rays, std::uint64_t seed = 1);

}  // namespace radwalk
