#pragma once
// Which patch causes the discretisation error: each shooter's first-order share of the squared error
// (derivation and contract: docs/theory/discretisation_error.md, "Which patch causes the error: the shooter
// attribution").
//
// The error e = (I - H)^{-1} d (solve/discretisation_error.h) is driven by d_k = sum_j s_{j->k}, the fluctuation
// shot by each patch j to each receiver k (solve/fluctuation_source.h). The squared error
//   Phi = sum_{i,c} A_i e_ic^2
// is a sum over the shooters: with the adjoint psi_c = (I - H_c)^{-T} (A e_c) (per channel c),
//   Phi = sum_{k,c} psi_kc d_kc = sum_j c_j,     c_j = sum_{k,c} psi_kc s_{j->k,c},
// c_j the part of Phi that j's fluctuation causes (to first order: removing j's fluctuation removes c_j from Phi,
// up to the second-order term of j's own part of e). Splitting j in 4 removes about 3/4 of its fluctuation, so c_j
// is the gain of splitting the shooter j, where A_i |e_i|^2 is the gain of splitting the receiver i only when i's
// own error comes from its own size.
//
// Estimated without bias from the two independent replicates d^(0), d^(1) of the source: e^(r) = (I - H)^{-1} d^(r),
// psi^(r)_c = (I - H_c)^{-T} (A e^(r)_c), and each replicate's shots weighted by the other replicate's adjoint,
//   c_j = (1/2) sum_{k,c} (psi^(1)_kc s^(0)_{j->k,c} + psi^(0)_kc s^(1)_{j->k,c}),
// so that the noise of j's own shots is not squared into c_j (E[psi^(1) s^(0)] = E[psi] E[s]), and exactly
//   sum_j c_j = sum_{i,c} A_i e^(0)_ic e^(1)_ic,
// an unbiased estimate of Phi (the product of two independent estimates of e). A single c_j may be negative (a
// shooter whose fluctuation cancels another's error, or noise).
#include <cstdint>
#include <vector>

#include "core/types.h"
#include "solve/block_jacobi.h"
#include "patch/patch_set.h"
#include "solve/fluctuation_source.h"
#include "solve/problem.h"
#include "visibility/visibility.h"

namespace radwalk {

struct ShooterAttribution {
  std::vector<double> share;  // c_j per patch (B's units squared times area, as A_i |e_i|^2)
  double total = 0;           // sum_{i,c} A_i e^(0)_ic e^(1)_ic, which sum_j c_j equals up to rounding
  long rays = 0;              // the shot rays traced again (a third of the source's, a half without emitters)
  long sweeps = 0;            // of the two solves
  double seconds = 0;
};

// h: the problem whose H = diag(rho) F the error e was solved with (every row of F: not row-distributed, checked);
// source: fluctuation_source(patches, visibility, B, directions, seed, 4, true) of the same arguments (its delta_m
// are shot again, the same shots). Values of ordinary size (the caller scales as discretisation_error does).
ShooterAttribution shooter_attribution(const PatchSet& patches, const Visibility& visibility,
                                       const RadiosityProblem& h, const PatchRgb& B, const FluctuationSource& source,
                                       int directions, std::uint64_t seed);

// The adjoint psi = (I - H)^{-T} W for a weight per patch and column: column 3 q + c of W (N x 3Q) belongs to
// channel c, psi_c = W_c + F^T diag(rho_c) psi_c by Jacobi sweeps to a relative change below 1e-7 (InputError after
// 100,000 sweeps: spectral radius of H near 1). F must hold every row (checked). The sweeps are added to `sweeps`.
RowBlock adjoint_block(const RadiosityProblem& p, const RowBlock& W, long& sweeps);

}  // namespace radwalk
