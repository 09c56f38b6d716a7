#pragma once
// The estimated discretisation error of a piecewise-constant radiosity solution: how far each patch's B is from
// the continuous radiosity averaged over the patch (derivation: docs/theory/discretisation_error.md).
//
// The patch averages Bbar of the continuous solution satisfy Bbar = E + H Bbar + d exactly
// (H = diag(rho) F), so the discrete solution B_h is off by
//   e = Bbar - B_h = (I - H)^{-1} d,
// estimated with d's estimate (solve/fluctuation_source.h) (Jacobi sweeps, solve/block_jacobi.h) and its variance propagated as the form
// factors' noise is (solve/error_propagation.h). The reported error B_disc is an empirical-Bayes root mean square
// of e given the estimate (a prior e_ic ~ N(0, t_c^2 B_ic^2) with t_c fitted over the patches of i's size class,
// prior_classes below, and never below the one fitted over all the patches, so that the estimate's own noise is not
// counted as error):
//   B_disc_ic^2 = max(w^2 e_ic^2 + w Var(e_ic), e_ic^2 - Var(e_ic)),  w = t_c^2 B_ic^2 / (t_c^2 B_ic^2 + Var(e_ic)).
#include <cstdint>
#include <vector>

#include "core/types.h"
#include "patch/patch_set.h"
#include "solve/problem.h"
#include "solve/shooter_attribution.h"
#include "visibility/visibility.h"

namespace radwalk {

struct DiscretisationError {
  PatchRgb estimate;        // e (signed): Bbar - B_h estimated
  PatchRgb standard_error;  // B_disc (above)
  int points = 0;           // per patch and replicate (fluctuation_source.h)
  int directions = 0;       // per point and kind
  long near_field_patches = 0;  // patches given more points for their near field (fluctuation_source.h)
  long rays = 0;
  long sweeps = 0;
  Rgb prior_relative = Rgb::Zero();  // t_c over all the patches (a size class's own, if larger: prior_classes)
  std::size_t prior_classes = 0;     // the size classes the prior was fitted in
  bool own_form_factors = false;  // true when H came from the estimate's own shot rays (p had no stored F)
  double seconds = 0;
  // The source d of e = (I - H)^{-1} d and its standard deviation (solve/fluctuation_source.h), kept for the
  // discretisation errors of measurements of the same solution (measurement_discretisation_error below).
  PatchRgb source, source_sd;
};

// The size classes of the empirical-Bayes prior: the counted patches (counted[i], area > 0) by level
// floor(log4(A_max / A_i)) from the largest, consecutive levels joined until a class holds kPriorClassPatches
// (the last class, if smaller, joins the one before); every other patch takes the class of the counted patch
// nearest to it in area. One class when there are fewer than 2 kPriorClassPatches counted patches or all are
// within a factor 4 of the largest (a uniform patching). Why: patches of one size are alike in how far off they can
// be, patches of different sizes are not. A hierarchy's small leaves sit where the radiosity is steep, and one
// prior over all of them, whose area is mostly large smooth leaves, shrank the noisy estimates of the small ones to
// nothing (on the spot-lit room at --target-error 0.01 a 1.25 mm wall leaf at the floor estimated at -0.22 +- 0.22
// for a true -0.49 got B_disc 0.001). A class's scale is kept at least the scene's: a class whose estimates are
// mostly noise fits a scale near 0 (on the furniture room at --max-edge 0.5 the per-value coverage fell from 0.959
// to 0.937 with the classes' own scales); docs/theory/discretisation_error.md, "From an estimate to an error bar".
inline constexpr std::size_t kPriorClassPatches = 64;
struct PriorClasses {
  std::vector<std::size_t> of;  // per patch
  std::size_t count = 1;
};
PriorClasses prior_classes(const std::vector<double>& area, const std::vector<bool>& counted);

// p: the problem B solves; when its F is empty (the ray kernel never stores F) the estimate's own shot rays give
// H (their noise is of second order in e). Collective over MPI when p's F is row-distributed; every process traces
// every patch's rays (the same numbers on every process). directions L >= 1 (fluctuation_source.h).
// attribution, if given: filled with each patch's share of the squared error as a shooter
// (solve/shooter_attribution.h), from the same source and H; left empty (share empty) when p's F is row-distributed.
DiscretisationError discretisation_error(const PatchSet& patches, const Visibility& visibility,
                                         const RadiosityProblem& p, const PatchRgb& B, int directions,
                                         std::uint64_t seed, ShooterAttribution* attribution = nullptr);

// The discretisation error of a measurement M_c = sum_i W_i B_ic (W = A R, solve/measurement.h): with the
// adjoint Psi = (I - H)^{-T} W (solve/form_factor_error.h, adjoint_weights) and the source d of the exact
// equation above,
//   eps_c = sum_i W_i e_ic = sum_j Psi_jc d_jc        (signed: the continuous M minus the discrete one),
//   Var(eps_c) = sum_j Psi_jc^2 Var(d_jc)            (d's rows are independent),
//   M_disc_c = sqrt(eps_c^2 + Var(eps_c))            (the root mean square of the error given eps under a flat
//                                                     prior: one number has no population to fit a prior to).
// p must hold every row of F; B the discrete solution (to a few digits).
struct MeasurementDiscretisationError {
  Rgb estimate = Rgb::Zero();        // eps
  Rgb estimate_sd = Rgb::Zero();     // sqrt(Var(eps))
  Rgb standard_error = Rgb::Zero();  // M_disc
  PatchRgb share;                    // Psi_jc d_jc per patch and channel: patch j's share of eps (sums to eps)
  long rays = 0;
  long sweeps = 0;
  double seconds = 0;
};
MeasurementDiscretisationError measurement_discretisation_error(const PatchSet& patches, const Visibility& visibility,
                                                                const RadiosityProblem& p, const PatchRgb& B,
                                                                const Eigen::VectorXd& W, int directions,
                                                                std::uint64_t seed);
// The same from a source already estimated (DiscretisationError::source and source_sd of the solution): no rays,
// one adjoint solve (rays 0).
MeasurementDiscretisationError measurement_discretisation_error(const RadiosityProblem& p, const PatchRgb& d,
                                                                const PatchRgb& d_sd, const Eigen::VectorXd& W);
// The same with the adjoint already solved (shared with other errors of the same measurement, e.g. its variance
// from F's noise, solve/group_mean_error.h): psi = adjoint_weights(p, W / r) (solve/form_factor_error.h), r > 0 the
// scale W was divided by (core/moments.h: W near the largest double); sweeps 0.
MeasurementDiscretisationError measurement_discretisation_error(const PatchRgb& psi, double r, const PatchRgb& d,
                                                                const PatchRgb& d_sd);

// The total error B_err = sqrt(B_se^2 + B_disc^2) per patch and channel (statistical and discretisation errors are
// independent); either may be empty (then the other is returned; both empty: empty).
PatchRgb total_error(const PatchRgb& B_se, const PatchRgb& B_disc);

}  // namespace radwalk
