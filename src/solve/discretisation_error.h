#pragma once
// The estimated discretisation error of a piecewise-constant radiosity solution: how far each patch's B is from
// the continuous radiosity averaged over the patch (derivation: docs/theory/discretisation_error.md).
//
// The patch averages Bbar of the continuous solution satisfy Bbar = E + H Bbar + d exactly
// (H = diag(rho) F), so the discrete solution B_h is off by
//   e = Bbar - B_h = (I - H)^{-1} d,
// estimated with d's estimate (solve/fluctuation_source.h) (Jacobi sweeps, solve/block_jacobi.h) and its variance propagated as the form
// factors' noise is (solve/error_propagation.h). The reported error is the root mean square of e given the
// estimate, as one standard deviation of an error of unknown sign:
//   B_disc_i = sqrt(e_i^2 + Var(e_i))      per channel.
#include <cstdint>

#include "core/types.h"
#include "patch/patch_set.h"
#include "solve/problem.h"
#include "visibility/visibility.h"

namespace radwalk {

struct DiscretisationError {
  PatchRgb estimate;        // e (signed): Bbar - B_h estimated
  PatchRgb standard_error;  // B_disc = sqrt(e^2 + Var(e))
  int points = 0;           // per patch and replicate (fluctuation_source.h)
  int directions = 0;       // per point and kind
  long rays = 0;
  long sweeps = 0;
  Rgb prior_relative = Rgb::Zero();  // t_c: the prior's relative scale of e, from all the patches
  bool own_form_factors = false;  // true when H came from the estimate's own shot rays (p had no stored F)
  double seconds = 0;
};

// p: the problem B solves; when its F is empty (the ray kernel never stores F) the estimate's own shot rays give
// H (their noise is of second order in e). Collective over MPI when p's F is row-distributed; every process traces
// every patch's rays (the same numbers on every process). directions L >= 1 (fluctuation_source.h).
DiscretisationError discretisation_error(const PatchSet& patches, const Visibility& visibility,
                                         const RadiosityProblem& p, const PatchRgb& B, int directions,
                                         std::uint64_t seed);

// The total error B_err = sqrt(B_se^2 + B_disc^2) per patch and channel (statistical and discretisation errors are
// independent); either may be empty (then the other is returned; both empty: empty).
PatchRgb total_error(const PatchRgb& B_se, const PatchRgb& B_disc);

}  // namespace radwalk
