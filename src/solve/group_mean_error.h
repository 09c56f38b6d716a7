#pragma once
// The estimated error of each group's mean radiosity (a material's, an object's): what a user reads off a solution
// per material, and what the per-patch target does not bound (docs/accuracy.md, "Accuracy on request").
//
// The per-patch errors of a piecewise-constant solution are correlated: the discretisation error e = (I - H)^{-1} d
// of the patches of one material, seen alike, has one sign (a sofa's cushions, lit at grazing angles along their
// creases, all read low), so a group's mean can be off by far more than the area-weighted RMS of its patches'
// errors (measured: a sofa +5.0 % at a per-patch estimate of 1.5 %). Per group g, over its counted patches
// (reflecting, non-emitting, as solve/target_error.h's relative_error), all channels together:
//   M_g      = sum_{i in g} A_i sum_c B_ic                       (3 A_g times the group's mean radiosity),
//   eps_g    = sum_c eps_gc,   eps_gc = sum_j Psi_gjc d_jc        (the signed discretisation error of M_g, from the
//                                                                  adjoint Psi_g = (I - H)^{-T} (A 1_g) and the
//                                                                  source d of the solution's own estimate:
//                                                                  solve/discretisation_error.h),
//   disc_g   = sqrt(eps_g^2 + (sum_c sd(eps_gc))^2) / M_g        (the channels' estimates share their rays: their
//                                                                  noise added as if fully correlated),
//   stat_g   = sqrt((sum_c sqrt(Var_F(M_gc)))^2 + S_g^2) / M_g   ("first-order": the form factors' noise exact to
//                                                                  first order, as solve/form_factor_error.h's
//                                                                  measurement_form_factor_error, from the same
//                                                                  adjoint: Var_F(M_gc) = sum_j (Psi_gjc rho_jc)^2
//                                                                  V_jc, V the calibrated gather variance of the
//                                                                  solve's own estimate of B_se, kappa = 1; the
//                                                                  channels share their rays: added as if fully
//                                                                  correlated, as disc_g's; S_g = sum_{i in g} A_i
//                                                                  sum_c s_ic the solver's own standard error s (a
//                                                                  walk's: its scores at the patches of a group are
//                                                                  correlated in ways not modelled, so bounded;
//                                                                  zero for the deterministic solvers), independent
//                                                                  of F's noise given F: the variances add),
//   stat_g   = sum_{i in g} A_i sum_c B_se_ic / M_g              ("bound", where F's noise has no model: F read
//                                                                  from a file, the analytic route's: the patches'
//                                                                  statistical errors added as if fully correlated,
//                                                                  a bound whatever their correlation; measured on
//                                                                  the furniture room it is several times the
//                                                                  first-order value, docs/accuracy.md),
//   total_g  = sqrt(disc_g^2 + stat_g^2).
// Where a group's error comes from: eps_g = sum_j Psi_gj . d_j, so patch j's share |sum_c Psi_gjc d_jc| (the
// dual-weighted residual of goal-oriented refinement: the source at j times j's importance for the group) says
// where splitting serves the group. It lies in the group's patches and in those that exchange light with them:
// a sofa's back 0.1 m from a wall is wrong because both the back and the wall behind it vary within their
// patches, and the wall, within the target itself, must be split for the sofa.
// Cost: one adjoint solve (Jacobi sweeps on F^T) per group, shared by both parts; no rays (V was measured by the
// solve's own statistical estimate).
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/types.h"
#include "patch/patch_grouping.h"
#include "patch/patch_set.h"
#include "solve/problem.h"

namespace radwalk {

struct GroupMeanError {
  std::string name;
  bool counted = false;     // has counted patches (else the numbers below are 0)
  double area = 0;          // of its counted patches
  double mean = 0;          // M_g / (3 A_g): its mean radiosity, channels averaged
  double estimate = 0;      // eps_g / M_g: the signed relative discretisation error (continuous minus discrete)
  double discretisation = 0, statistical = 0, total = 0;  // disc_g, stat_g, total_g (relative)
  // How stat_g was obtained: "first-order" (above), "first-order+walk-bound" (F's noise first order, the walks'
  // own part bounded) or "bound" (no model of F's noise).
  std::string statistical_kind = "bound";
  double statistical_bound = 0;  // sum_{i in g} A_i sum_c B_se_ic / M_g: the bound, whatever the kind
  std::vector<double> share;  // per patch j: |sum_c Psi_gjc d_jc| / M_g (kept only above keep_shares_above)
};

// The statistical model of a solution's B_se that the first-order stat_g needs (each empty when there is none).
struct GroupNoiseModel {
  PatchRgb gather_standard_error;  // sqrt(V_jc) per row (FormFactorError::gather_standard_error); empty: F's noise
                                   // has no model (stat_g the bound)
  PatchRgb solver_standard_error;  // the solver's own standard error per patch (a walk's); empty: it has none
};

// p: the problem B solves (every row of F); B, B_se (may be empty: stat 0) per patch; d, d_sd: the source of B's
// discretisation estimate and its standard deviation (DiscretisationError::source, source_sd); noise: B_se's model
// (stat_g first-order when it has a gather_standard_error of N rows, else the bound). The shares are kept for the
// groups whose total is above keep_shares_above (N doubles each).
std::vector<GroupMeanError> group_mean_errors(const PatchSet& patches, const PatchGrouping& grouping,
                                              const RadiosityProblem& p, const PatchRgb& B, const PatchRgb& B_se,
                                              const PatchRgb& d, const PatchRgb& d_sd,
                                              double keep_shares_above = HUGE_VAL,
                                              const GroupNoiseModel& noise = {});

}  // namespace radwalk
