#include "solve/target_error_stage.h"

#include <memory>
#include <utility>

#include "core/timer.h"
#include "solve/problem.h"
#include "solve/solve_options.h"
#include "solve/solve_radiosity.h"

namespace radwalk {

TargetErrorStage solve_target_error_stage(const PatchSet& patches, const Visibility& visibility,
                                          FormFactors form_factors, const TargetErrorStageOptions& options,
                                          TargetErrorStageEstimates* estimates) {
  TargetErrorStage stage;
  stage.form_factors = std::move(form_factors);
  stage.problem = std::make_shared<const RadiosityProblem>(make_problem(patches, SparseF(stage.form_factors.F)));
  const RadiosityProblem& problem = *stage.problem;
  SolveOptions solve;
  solve.tol = options.tol;
  solve.auto_direct_max_patches = kTargetStageDirectMaxPatches;
  solve.auto_iterative = "gmres";
  solve.max_iterations = default_max_iterations(solve.solver, patches.size());
  stage.solution = solve_radiosity(problem, solve);
  if (stage.solution.status != SolveStatus::converged) return stage;
  const PatchRgb own = stage.solution.B_se.rows() == stage.solution.B.rows() ? stage.solution.B_se : PatchRgb();
  const Timer timer;
  std::optional<FormFactorError> statistical =
      add_form_factor_error(patches, visibility, stage.form_factors, problem, stage.solution);
  const double seconds = timer.seconds();
  // B_se's model for the groups' means (solve/group_mean_error.h): F's row noise, measured above, and the solver's own.
  if (statistical) {
    stage.noise.gather_standard_error = statistical->gather_standard_error;
    stage.estimate_rays += statistical->calibration.rays;
  }
  stage.noise.solver_standard_error = own;
  std::optional<DiscretisationError> discretisation;
  if (options.discretisation_directions > 0) {
    ShooterAttribution attribution;
    discretisation = discretisation_error(patches, visibility, problem, stage.solution.B,
                                          options.discretisation_directions, options.seed,
                                          options.attribute_shooters ? &attribution : nullptr);
    stage.shooter_share = std::move(attribution.share);
    stage.estimate_rays += discretisation->rays;
    stage.solution.B_disc = discretisation->standard_error;
    stage.source = discretisation->source;
    stage.source_sd = discretisation->source_sd;
  }
  if (estimates) {
    estimates->solver_standard_error = own;
    estimates->statistical = std::move(statistical);
    estimates->statistical_seconds = seconds;
    estimates->discretisation = std::move(discretisation);
  }
  return stage;
}

}  // namespace radwalk
