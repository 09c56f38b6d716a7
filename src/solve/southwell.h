#pragma once
// Southwell iteration (progressive refinement by shooting, Cohen et al. 1988) for (I - H_c) B_c = E_c,
// H_c = diag(rho_c) F. It keeps B (radiosity already shot) and the unshot radiosity dB = E - (I - H) B, which is
// exactly the residual (B^0 = 0, dB^0 = E). A shot from patch i, the one with the most unshot power
// A_i sum_c |dB_ic|, moves s_c = dB_ic / D_ic into B_ic (D_ic = 1 - rho_ic F_ii) and distributes it along
// column i of H, with no reciprocity assumed:
//   dB_jc += rho_jc F_ji s_c  (j != i),   dB_ic = 0.
// Column access needs F^T, built once (as much memory again as F). A tournament tree keeps both the next patch to
// shoot and max_i |dB_ic| per channel, so the relative residual (residual.h) is known after every shot at
// O(log N) per touched patch. iterations = shots; the history has one entry per N shots. The returned residual
// is recomputed exactly from B at the end. Progress ("southwell shots", solve/iteration_progress.h) every N shots.
// Converges for H >= 0 with radius(H) < 1; checked before shooting and watched while shooting (convergence.h).
#include "solve/problem.h"
#include "core/solution.h"
#include "solve/solve_options.h"

namespace radwalk {

// Throws InputError for a bad problem or options. info["ambient_r|g|b"]: the ambient term of the result.
Solution solve_southwell(const RadiosityProblem& p, const SolveOptions& options = {});

// Cohen et al.'s ambient term, for display only (never added to B by any solver): with the unshot radiosity
// dB = E - (I - H) B of an approximate B, the area-weighted mean reflectance rho_avg,c and the interreflection
// factor R_c = 1 / (1 - rho_avg,c),
//   ambient_c = R_c sum_j A_j dB_jc / sum_j A_j,   returned per patch as rho_ic * ambient_c (W/m^2).
// Throws NumericalError if some rho_avg,c >= 1 (the factor R_c does not exist); B must have a row per patch.
PatchRgb southwell_ambient(const RadiosityProblem& p, const PatchRgb& B);

}  // namespace radwalk
