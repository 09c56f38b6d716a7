#pragma once
// The residual of the radiosity system and the norm every deterministic solver stops on.
//
// Per channel c:  r_c = E_c - (I - H_c) B_c = E_c + rho_c .* (F B_c) - B_c,  H_c = diag(rho_c) F.
// Relative residual:  max_c ||r_c||_inf / s_c  with the scale s_c = ||E_c||_inf; a dark channel (E_c = 0) is
// measured against the largest emission max_c ||E_c||_inf, and a scene without emission absolutely (s = 1).
// The infinity norm makes it independent of N and gives the error bound
//   ||B_c - B*_c||_inf / ||B*_c||_inf <= kappa_inf(I - H_c) * ||r_c||_inf / ||E_c||_inf.
#include "core/types.h"
#include "solve/problem.h"

namespace radwalk {

// F B for every channel (F in float, products and sums in double). B is N x 3.
PatchRgb multiply_F(const SparseF& F, const PatchRgb& B);

// r = E + rho .* (F B) - B (W/m^2), N x 3. Collective when p's F is row-distributed (problem.h): each rank's
// rows, then exchanged, so every rank has every row (the same bits as one process).
PatchRgb residual(const RadiosityProblem& p, const PatchRgb& B);

// The per-channel scale s_c described above (always > 0).
Rgb residual_scale(const PatchRgb& E);

// max_c ||r_c||_inf / s_c for a residual r already computed.
double relative_norm(const PatchRgb& r, const Rgb& scale);

// The diagonal of I - H: D_ic = 1 - rho_ic F_ii (1 where F_ii is not stored), N x 3. Collective when F is
// row-distributed (each row's from the rank holding it, exchanged).
PatchRgb system_diagonal(const RadiosityProblem& p);

// relative_norm(residual(p, B), residual_scale(p.E)). Collective when F is row-distributed: the norm of each
// rank's rows, then the largest over the ranks.
double relative_residual(const RadiosityProblem& p, const PatchRgb& B);

}  // namespace radwalk
