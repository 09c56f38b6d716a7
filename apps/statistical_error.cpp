#include "apps/statistical_error.h"

#include <cmath>
#include <optional>
#include <string>

#include "apps/pipeline.h"
#include "core/format_number.h"
#include "core/moments.h"
#include "core/timer.h"
#include "formfactor/form_factor_noise.h"
#include "solve/form_factor_error.h"
#include "solve/target_error.h"
#include "visibility/embree_visibility.h"

namespace radwalk::app {

std::string percent(double x) {
  return format_number(100 * x, 2) + " %";
}

std::string add_statistical_error(const PatchSet& patches, const FormFactors& ff, const RadiosityProblem& problem,
                                  Solution& solution, RunSummary& summary, GroupNoiseModel* noise) {
  const Eigen::Index N = static_cast<Eigen::Index>(patches.size());
  if (solution.B.rows() != N) return {};
  const bool walks = solution.B_se.rows() == N;
  const PatchRgb own_se = walks ? solution.B_se : PatchRgb();
  Timer timer;
  std::optional<FormFactorError> error;
  if (has_noise_model(ff)) {
    const EmbreeVisibility visibility(patches);
    error = add_form_factor_error(patches, visibility, ff, problem, solution);
  } else {
    solution.B_se = walks ? own_se : PatchRgb::Zero(N, 3);  // F's noise unknown: the solver's own part alone
  }
  if (noise) {
    noise->gather_standard_error = error ? error->gather_standard_error : PatchRgb();
    noise->solver_standard_error = own_se;
  }
  return report_statistical_error(patches, ff, solution, own_se, error ? &*error : nullptr, timer.seconds(), summary);
}

std::string report_statistical_error(const PatchSet& patches, const FormFactors& ff, const Solution& solution,
                                     const PatchRgb& own_se, const FormFactorError* error, double seconds,
                                     RunSummary& summary) {
  const Eigen::Index N = static_cast<Eigen::Index>(patches.size());
  if (solution.B.rows() != N) return {};
  auto& j = summary.json()["error_estimate"];
  auto& stat = j["statistical"];
  const bool walks = own_se.rows() == N;
  const double walks_relative = walks ? relative_error(patches, solution.B, own_se) : 0.0;
  if (walks) stat["walks_relative"] = walks_relative;
  const double total = relative_error(patches, solution.B, solution.B_se);
  if (!error) {
    // F read from a file records no sampling; the analytic route's visibility estimates have their row standard
    // errors (the CSV's row_std_error) but are not propagated yet.
    const bool analytic = !ff.row_std_error.empty();
    const std::string what = analytic ? "the analytic form factors' visibility noise (their row_std_error) is not "
                                        "propagated"
                                      : "the noise of the form factors read from the file is not included";
    stat["form_factors"] = "not included: " + what;
    stat["relative"] = total;
    return "estimated statistical error e = " + percent(total) + (walks ? " (the walks' own; " : " (") + what + ")";
  }
  const SamplingCalibration& calibration = error->calibration;
  const PropagatedVariance& propagated = error->propagation;
  const double from_F = relative_error(patches, solution.B, error->standard_error);
  stat["relative"] = total;
  stat["form_factors_relative"] = from_F;
  stat["sampling_factor_rays"] = calibration.factors.rays;
  stat["sampling_factor_rays_measured"] = calibration.rays_measured;
  stat["sampling_factor_emitter"] = calibration.factors.emitter;
  stat["sampling_factor_emitter_measured"] = calibration.emitter_measured;
  stat["coverage_factor"] = calibration.factors.coverage;
  stat["calibration_rows"] = calibration.rows;
  stat["calibration_replicates"] = calibration.replicates;
  stat["calibration_rays"] = calibration.rays;
  stat["probes"] = propagated.probes;
  stat["propagation_sweeps"] = propagated.sweeps;
  stat["method"] = "first-order propagation of each row's gather variance, Var(B_i) = sum_j G_ij^2 rho_j^2 V_j "
                   "(docs/theory/error_estimate.md)";
  summary.add_timing("error_estimate", seconds);
  std::string line = "estimated statistical error e = " + percent(total) +
                     " (1 standard deviation, relative to B over the reflecting patches; from the form factors' noise " +
                     percent(from_F);
  if (walks) line += ", the walks' own " + percent(walks_relative);
  return line + ")";
}

}  // namespace radwalk::app
