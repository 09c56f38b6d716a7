#pragma once
// Grey diffuse radiative heat exchange by the net-radiation method, written as radwalk's radiosity system
// B = E + diag(rho) F B so that every deterministic solver runs it. Derivation: docs/theory/net_radiation.md.
//
// Patch i has emissivity eps_i in (0, 1] and either a known temperature T_i (K) or a known net heat flux q_i
// (W/m^2, leaving the surface). Its radiosity J_i (W/m^2) and irradiance G_i satisfy
//   G_i = sum_j F_ij J_j + s_i sigma T_a^4        (s_i: the sky view factor, the part of the hemisphere that
//                                                  reaches the ambient at T_a, emissivity 1)
//   J_i = eps_i sigma T_i^4 + (1 - eps_i) G_i      (emission plus reflection)
//   q_i = J_i - G_i = eps_i (sigma T_i^4 - G_i)    (net flux leaving)
// so, row by row,
//   known T:  J_i - (1 - eps_i) sum_j F_ij J_j = eps_i sigma T_i^4 + (1 - eps_i) s_i sigma T_a^4
//   known q:  J_i -             sum_j F_ij J_j = q_i + s_i sigma T_a^4
// which is B = S + diag(rho) F B with rho_i = 1 - eps_i (known T) or 1 (known q) and the source S above. S may be
// negative (a surface given a net heat gain, q_i < 0) while the radiosity solvers take E >= 0, so S is split by
// sign and both parts are solved at once as channels of one problem with the same rho (one factorisation):
//   channel 0: S+ = max(S, 0),  channel 1: S- = max(-S, 0),  channel 2: S+ (a copy: all channels are solved),
// and J = B_0 - B_1 (linearity). A patch with eps = 1 and known T has rho = 0: J_i = sigma T_i^4 directly.
// The temperature of a known-q patch follows from q_i = eps_i (sigma T_i^4 - G_i): sigma T_i^4 = G_i + q_i / eps_i.
#include <string>
#include <vector>

#include "core/solution.h"
#include "formfactor/sparse_f.h"
#include "solve/problem.h"

namespace radwalk {

// The Stefan-Boltzmann constant, W m^-2 K^-4 (CODATA 2018; exact in the SI of 2019 as 2 pi^5 k^4 / (15 h^3 c^2)).
inline constexpr double kStefanBoltzmann = 5.670374419e-8;

// The thermal condition of one patch.
struct SurfaceCondition {
  double emissivity = 1;           // in (0, 1]
  bool temperature_given = true;   // true: temperature is known, heat_flux is solved; false: the reverse
  double temperature = 0;          // K (>= 0) when given
  double heat_flux = 0;            // W/m^2, net leaving, when the temperature is not given
};

// The enclosure: form factors, areas, conditions, and where the rays not caught by F go.
struct NetRadiationInput {
  std::vector<double> area;                 // N patch areas (m^2 when lengths are metres)
  std::vector<SurfaceCondition> surface;    // N conditions
  std::vector<double> sky;                  // N sky view factors s_i in [0, 1] (empty: 0 everywhere)
  double ambient_temperature = 0;           // T_a, K
};

// The source S_i and the reflectance rho_i of the radiosity form above, per patch. Throws InputError naming the
// first patch whose condition is out of range (eps outside (0, 1], T < 0 or not finite, q not finite, s outside
// [0, 1]) or when no patch fixes the level of the temperatures: every patch has a known flux and nothing reaches
// an ambient (sum of s_i A_i = 0), so (I - F) J = q has no unique solution.
struct NetRadiationCoefficients {
  std::vector<double> rho, source;
};
NetRadiationCoefficients net_radiation_coefficients(const NetRadiationInput& input);

// The radiosity problem of the net-radiation system (channels as above), with F as given (N x N; row-distributed
// blocks kept). area from input.
RadiosityProblem net_radiation_problem(const NetRadiationInput& input, SparseF F, RowBlocks row_blocks = {});

// J from a solution of net_radiation_problem: B_0 - B_1 per patch.
std::vector<double> radiosity_of(const Solution& solution);

// Everything per patch once J is known: the irradiance G, the net flux q (W/m^2), the net heat Q = A q (W), the
// temperature T (given or solved). F must hold every row. Throws InputError naming the patch when a known-q patch
// has no temperature (sigma T^4 = G + q / eps < 0: it would absorb more than it is irradiated with).
struct NetRadiationResult {
  std::vector<double> J, G, q, Q, T;
};
NetRadiationResult net_radiation_result(const NetRadiationInput& input, const SparseF& F, std::vector<double> J);

// The dense reference: (I - diag(rho) F) J = S solved by Eigen's partial-pivoting LU on the dense matrix (tests
// and small checks; O(N^3)).
std::vector<double> dense_net_radiation(const NetRadiationInput& input, const SparseF& F);

}  // namespace radwalk
