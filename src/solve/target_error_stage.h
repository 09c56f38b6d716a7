#pragma once
// One step's stage of accuracy on request (solve/target_error.h, TargetErrorWork) once its F is traced: the one
// definition that `radwalk solve --target-error` (apps/target_error.h) and radwalk.solve_to_target_error run, so
// that the same F gives the same B, B_se and B_disc on both; how F is traced (the command's route, or Python's
// recommended one) and what is reported stay with the caller.
#include <cstdint>
#include <optional>

#include "formfactor/form_factors.h"
#include "patch/patch_set.h"
#include "solve/discretisation_error.h"
#include "solve/form_factor_error.h"
#include "solve/target_error.h"
#include "visibility/visibility.h"

namespace radwalk {

struct TargetErrorStageOptions {
  double tol = 1e-10;                 // the automatic solver's tolerance (solve/solve_options.h)
  int discretisation_directions = 16;  // L of solve/fluctuation_source.h; <= 0: B_disc not estimated
  std::uint64_t seed = 1;              // of the discretisation estimate's rays
  // Also each patch's shooter share of the squared discretisation error (stage.shooter_share,
  // solve/shooter_attribution.h; about a third more of the estimate's rays), for the refinement.
  bool attribute_shooters = false;
};

// What the stage's estimates measured, for a caller that reports them (the CLI's JSON and summary lines): each
// set only when computed.
struct TargetErrorStageEstimates {
  PatchRgb solver_standard_error;              // the solver's own B_se before F's noise (empty: it has none)
  std::optional<FormFactorError> statistical;  // F's noise in B (none: F records no tracing, or no convergence)
  double statistical_seconds = 0;              // its time, the Embree scene of `visibility` not included
  std::optional<DiscretisationError> discretisation;
};

// The direct solve's limit in a stage: a run solves again at every step, so the dense LU only where it costs about a
// tenth of a second (kAutoDirectMaxPatches is where it costs about a second), and GMRES above (Gauss-Seidel
// preconditioned: robust near radius 1, as the LU is). On the furniture room (`--target-error 0.02 --seed 2`) the
// LU took 1.2 s of the last step's 3.0 s at 1,971 leaves, GMRES 0.02 s, with the same leaves and errors.
inline constexpr long kTargetStageDirectMaxPatches = 1000;

// The problem of `patches` with a copy of F, kept as stage.problem (the stage keeps form_factors, with its record
// of how F was traced, for the caller's per-patch diagnostics), solved by the automatic solver to options.tol within
// default_max_iterations, directly up to kTargetStageDirectMaxPatches and by GMRES above; when it converged, B_se =
// the solver's own error combined with F's noise (add_form_factor_error, solve/form_factor_error.h) and B_disc = the discretisation error of B
// (discretisation_error, solve/discretisation_error.h) with options.discretisation_directions and options.seed,
// with its source d and d's standard deviation in stage.source and stage.source_sd, and B_se's model in stage.noise
// (F's row noise, when F records its tracing, and the solver's own: the groups' means' first-order statistical part).
// `visibility` is of `patches`. estimates, if given, receives what the estimates measured.
TargetErrorStage solve_target_error_stage(const PatchSet& patches, const Visibility& visibility,
                                          FormFactors form_factors, const TargetErrorStageOptions& options,
                                          TargetErrorStageEstimates* estimates = nullptr);

}  // namespace radwalk
