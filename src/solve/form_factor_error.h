#pragma once
// The variance of a radiosity solution B caused by the Monte Carlo noise of the traced form factors it was solved
// with: the sampling factors measured on replicated rows (formfactor/sampling_factor.h), each row's gather variance
// (formfactor/form_factor_noise.h) and its first-order propagation through (I - diag(rho) F)^{-1}
// (solve/error_propagation.h). Derivation: docs/theory/error_estimate.md.
#include <optional>

#include "core/solution.h"
#include "formfactor/form_factors.h"
#include "formfactor/sampling_factor.h"
#include "patch/patch_set.h"
#include "solve/error_propagation.h"
#include "solve/problem.h"
#include "visibility/visibility.h"

namespace radwalk {

// Scale before squaring (core/moments.h): B is divided by s = moment_scale(max B) before the variances are formed
// and the standard errors multiplied back, so that B up to the largest double gives finite results.
struct FormFactorError {
  PatchRgb standard_error;  // sqrt(Var(B_i)) per patch and channel from F's noise
  // sqrt(V_jc) per row and channel: the standard error of row j's gather (F B)_j with the mean sampling factors
  // and kappa = 1 (a sum over many rows: measurement_form_factor_error below), for the variance of measurements
  // and group means of the same solution, Var(M_c) = sum_j (Psi_jc rho_jc)^2 V_jc, without tracing again.
  PatchRgb gather_standard_error;
  SamplingCalibration calibration;
  PropagatedVariance propagation;
};

// p: the problem B solves (its F the estimate: every row, or over MPI this process's row block, p.row_blocks; then
// collective, and the same result on every process as on one); ff: how that F was traced
// (has_noise_model(ff); its own F may have been moved into p); B: the solution (N x 3); `visibility` of `patches`.
FormFactorError form_factor_error(const PatchSet& patches, const Visibility& visibility, const FormFactors& ff,
                                  const RadiosityProblem& p, const PatchRgb& B, int probes = 16);

// B_se of a solution from the form factors it was solved with: when ff records how F was traced
// (has_noise_model(ff)), F's noise propagated to B (form_factor_error above) combined with the solver's own
// standard error (combined_standard_error below; a walk's own noise is independent of F's given F, so the variances
// add: Var(B) = E[Var(B | F)] + Var(E[B | F])), and the estimate returned; otherwise (F read from a file, or the
// analytic route's) the solver's own alone, and nothing returned. The solver's own is solution.B_se when it has
// one row per patch, else zero. Sets solution.B_se (N x 3); nothing when B does not have N rows. Arguments as for
// form_factor_error.
std::optional<FormFactorError> add_form_factor_error(const PatchSet& patches, const Visibility& visibility,
                                                     const FormFactors& ff, const RadiosityProblem& p,
                                                     Solution& solution);

// sqrt(a^2 + b^2) per entry without squaring values near the largest double: the standard error of the sum of two
// independent errors (a walk's own and the form factors' noise).
PatchRgb combined_standard_error(const PatchRgb& a, const PatchRgb& b);

// The adjoint weights Psi = (I - H)^{-T} W of a measurement M_c = sum_i W_i B_ic (per channel: Psi_c = W +
// F^T diag(rho_c) Psi_c, Jacobi sweeps to a relative change below 1e-10; InputError after 100,000 sweeps), so that
// for any source d, sum_i W_i ((I - H)^{-1} d)_ic = sum_j Psi_jc d_jc. p's F must hold every row (checked);
// the sweeps are added to `sweeps`.
PatchRgb adjoint_weights(const RadiosityProblem& p, const Eigen::VectorXd& W, long& sweeps);

// The variance of a measurement M_c = sum_i W_i B_ic (W = A R, solve/measurement.h) from F's noise: with
// Psi = (I - H)^{-T} W (the adjoint, by Jacobi sweeps of Psi = W + F^T diag(rho) Psi to a relative change below
// 1e-10), dM = sum_j Psi_j rho_j dg_j and so
//   Var(M_c) = sum_j (Psi_jc rho_jc)^2 V_jc                       (V: the scaled gather variance, as above),
// exact to first order (no probes). B: the radiosity (any accurate estimate: V needs it only to a few per cent).
struct MeasurementError {
  Rgb standard_error = Rgb::Zero();  // sqrt(Var(M_c)) (B and W scaled before squaring, as above)
  SamplingCalibration calibration;
  long sweeps = 0;
};
MeasurementError measurement_form_factor_error(const PatchSet& patches, const Visibility& visibility,
                                               const FormFactors& ff, const RadiosityProblem& p, const PatchRgb& B,
                                               const Eigen::VectorXd& W);

}  // namespace radwalk
