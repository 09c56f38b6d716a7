#pragma once
// Closed cavities of a heat-exchange problem: sets of known-flux patches that exchange (almost) no radiation
// with anything that fixes a temperature, so that radiation leaves their radiosity undetermined. Derivation
// and the rule for near-closed sets: docs/heat-exchange.md, "Closed cavities".
//
// A known-flux patch's row of the net-radiation system (solve/net_radiation.h) is
//   J_i - sum_j F_ij J_j = q_i + s_i sigma T_a^4.
// Let C be a set of known-flux patches none of whose rows reaches outside C (F_ij = 0 for j not in C, no sky
// s_i, nothing into backs b_i: every row of F_CC sums to 1). Its block is (I - F_CC) J_C = q_C. The constant
// vector spans the null space of I - F_CC (a stochastic matrix, irreducible on a connected C), so J_C is
// determined only up to a uniform value; with reciprocity the left null vector is the areas
// (sum_i A_i (delta_ij - F_ij) = A_j - A_j sum_i F_ji = 0), so a solution exists only when
// sum_{i in C} A_i q_i = 0: re-radiating faces (q = 0) give infinitely many solutions, any other given fluxes
// with a non-zero sum none (the heat put in has no way out but conduction). Either way radiation does not give C a temperature.
//
// With a traced (sparse, noisy) or float-rounded F, a truly closed C has row sums 1 - O(1e-7) and an
// enclosure with a tiny opening has a block that is determined but so ill-conditioned that J_C follows the
// rounding and the rays that happened to leak. The rule: C is a cavity when its leak fraction
//   lambda_C = max(out, in) / A_C,
//   out = sum_{i in C} A_i (1 - sum_{j in C} F_ij)   (to other patches, the sky, backs, row deficit),
//   in  = sum_{j not in C} sum_{i in C} A_j F_ji    (what the rest sends into C),
// the fraction of C's own emitted radiation it exchanges with everything else (both directions, so a one-way
// entry of a traced F counts), is below kCavityLeak. The sets C tested are the connected components, through
// non-zero F_ij or F_ji, of the known-flux patches (a known-temperature patch fixes its J up to reflection,
// so the sets end there).
#include <cstdint>
#include <vector>

#include "formfactor/sparse_f.h"
#include "solve/net_radiation.h"

namespace radwalk {

// The leak fraction below which a set of known-flux patches is taken as closed: its radiative coupling to the
// rest, 4 sigma T^3 lambda A_C = 5.7e-4 W/K per m^2 of it at 293 K, is smaller than conduction through any
// solid wall (1 cm of wood: 13 W/(m^2 K)), so radiation does not set its temperature; and 1e-4 lies three
// orders of magnitude above the float rounding of F's row sums (2^-24 per entry), which otherwise decides
// J_C.
inline constexpr double kCavityLeak = 1e-4;

struct ClosedCavity {
  std::vector<std::size_t> patches;  // ascending
  double area = 0;                   // sum A_i, m^2
  double leak = 0;                   // lambda_C (above)
  double given_Q = 0;                // sum A_i q_i over its patches, W (0 for re-radiating faces)
};

// The cavities of the system with form factors F (N x N, every row held; a traced row's entries are fractions
// of its rays, so 1 - its sum over C includes its sky and back fractions) and the areas and conditions of
// `input`: the connected components of known-flux patches whose leak fraction is below `leak_threshold`, in
// order of their first patch. Sequential and deterministic.
std::vector<ClosedCavity> closed_cavities(const SparseF& F, const NetRadiationInput& input,
                                          double leak_threshold = kCavityLeak);

}  // namespace radwalk
