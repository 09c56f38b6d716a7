#pragma once
// Sensitivities of the groups' net heat to the groups' emissivities and temperatures in the net-radiation system
// (solve/net_radiation.h), by one adjoint solve per response group. Derivation: docs/theory/net_radiation.md,
// "Sensitivities".
//
// With A = I - diag(rho) F, A J = S and, for a response group G, Q_G = sum_{i in G} A_i q_i, where only the
// known-temperature patches' q_i = eps_i (sigma T_i^4 - G_i) depend on the parameters (a known-flux patch's Q is
// given), the adjoint psi of G solves
//   A^T psi = F^T a,    a_i = A_i eps_i for the known-temperature patches i of G, 0 elsewhere,
// and for every known-temperature patch k (1[k in G] the indicator)
//   dQ_G / d eps_k = (sigma T_k^4 - G_k) (A_k 1[k in G] - psi_k)          (W per unit emissivity)
//   dQ_G / d T_k   = 4 eps_k sigma T_k^3 (A_k 1[k in G] - psi_k)            (W/K).
// A known-flux patch's emissivity changes only its own temperature and its temperature is not an input, so both
// derivatives are 0 there. A group parameter moves every patch of the group together: dQ_G/d eps_H = sum_{k in H}
// dQ_G/d eps_k, and the same for T. At eps_k = 1 the derivative is the left one (eps <= 1), the smooth extension.
#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "formfactor/sparse_f.h"
#include "solve/net_radiation.h"

namespace radwalk {

struct NetRadiationSensitivity {
  // rows: the response groups in the order asked; columns: every parameter group 0..groups-1.
  Eigen::MatrixXd dQ_deps;  // W (per unit emissivity)
  Eigen::MatrixXd dQ_dT;    // W/K
  std::vector<long> iterations;     // BiCGSTAB iterations of each adjoint solve
  std::vector<double> residual;     // and its relative residual
};

// input, F (N x N, every row) and result r of a solved net-radiation system; group[i] in [0, groups) for every
// patch; responses: the response groups. The adjoint systems are solved by Eigen's BiCGSTAB (diagonal
// preconditioner) to a relative residual of 1e-13; InputError when one does not reach 1e-9.
NetRadiationSensitivity net_radiation_sensitivity(const NetRadiationInput& input, const SparseF& F,
                                                  const NetRadiationResult& r, const std::vector<std::int32_t>& group,
                                                  int groups, const std::vector<int>& responses);

}  // namespace radwalk
