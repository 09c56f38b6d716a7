// radwalk measure SCENE --response SPEC [--method M]: one measurement M = <R, B>_A = sum_i A_i R_i B_i with its
// standard error (walk/measure_by_method.h: every method; apps/measure_response.h: the response).
#include <cmath>
#include <cstdio>
#include <string>

#include "apps/measure_response.h"
#include "apps/options.h"
#include "apps/pipeline.h"
#include "apps/run_metadata.h"
#include "apps/scene_camera.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/timer.h"
#include "formfactor/form_factor_noise.h"
#include "solve/form_factor_error.h"
#include "solve/response_spec.h"
#include "solve/solve_radiosity.h"
#include "visibility/embree_visibility.h"
#include "walk/measure_by_method.h"

namespace radwalk::app {

int run_measure(const MeasureCommand& command) {
  RunSummary summary("measure", command.scene.argv);
  Mesh mesh;
  const PatchSet patches = load_patches(command.scene, summary, mesh);
  SceneCamera fitted;
  const Response response =
      measure_response(command.response, command.scene.scene, patches, patch_groups(mesh, patches), mesh.groups,
                       command.camera, command.width, command.height, &fitted);
  if (command.response == "camera")
    summary.json()["camera"] = camera_json(fitted, patches, command.width, command.height);
  MeasureOptions options;
  options.method = command.method;
  options.walks = command.walks;
  options.walk = command.walk;
  options.walk.seed = command.scene.seed;
  options.importance_sweeps = command.importance_sweeps;
  options.defensive = command.defensive;
  options.theory = command.theory;
  check_measure_options(options, patches.size());  // before any form factor is traced
  ThreadLimit limit(command.scene.threads);
  Measurement measurement;
  std::string form_factor_part;  // what the standard error covers besides the walks
  Rgb M_disc = Rgb::Zero();      // the estimated discretisation error (matrix-kernel methods)
  bool has_disc = false;
  if (!measure_needs_form_factors(options)) {
    const auto n = static_cast<Eigen::Index>(patches.size());
    const RadiosityProblem problem = make_problem(patches, SparseF(n, n));
    const EmbreeVisibility visibility(patches);
    measurement = measure_by_method(problem, &patches, &visibility, response, options);
  } else {
    FormFactors ff = obtain_form_factors(command.scene, command.ff, patches, summary);
    const RadiosityProblem problem = make_problem(patches, std::move(ff.F));
    measurement = measure_by_method(problem, nullptr, nullptr, response, options);
    Timer timer;
    const PatchRgb B = discrete_solution(patches, problem);
    summary.json()["error_estimate"]["statistical"] =
        add_form_factor_error(patches, ff, problem, B, response, measurement, form_factor_part);
    summary.add_timing("error_estimate", timer.seconds());
    double seconds = 0;
    const nlohmann::json disc = add_measurement_discretisation_error(
        patches, problem, B, response, command.discretisation_directions, command.scene.seed, M_disc, seconds);
    if (!disc.is_null()) {
      summary.json()["error_estimate"]["discretisation"] = disc;
      summary.add_timing("discretisation_error", seconds);
      has_disc = true;
    }
  }
  const MeasureEstimate& est = measurement.estimate;
  const bool deterministic = measurement.deterministic;
  const bool importance = is_importance_measure(command.method);
  if (importance)
    summary.json()["importance"] = {{"source", measurement.importance_source},
                                    {"sweeps", command.importance_sweeps},
                                    {"defensive", measurement.defensive}};
  summary.add_timing("measure", est.seconds);

  std::fprintf(report_stream(), "%s: M = <R, B>_A over %s = (%.9g, %.9g, %.9g)", command.method.c_str(), response.what.c_str(),
              est.M(0), est.M(1), est.M(2));
  if (!deterministic || !form_factor_part.empty()) {
    std::fprintf(report_stream(), " +- (%.3g, %.3g, %.3g) (standard error", est.se(0), est.se(1), est.se(2));
    if (!deterministic) std::fprintf(report_stream(), ", %ld walks", est.walks);
    std::fprintf(report_stream(), "%s)", form_factor_part.c_str());
  }
  std::fprintf(report_stream(), ", %.3f s\n", est.seconds);
  if (has_disc) {
    Rgb total;
    summary.json()["error_estimate"]["total"] = measurement_total_error(est.se, M_disc, total);
    std::fprintf(report_stream(),
                 "estimated discretisation error of M (%.3g, %.3g, %.3g), total error (%.3g, %.3g, %.3g) (1 standard "
                 "deviation: statistical and discretisation combined)\n",
                 M_disc(0), M_disc(1), M_disc(2), total(0), total(1), total(2));
  } else if (!measure_needs_form_factors(options)) {
    std::fprintf(report_stream(), "discretisation error of M: not estimated (the ray kernel computes no B to "
                                  "estimate it from)\n");
    summary.json()["error_estimate"]["discretisation"] = "not estimated: the ray kernel computes no B";
  }
  if (command.theory && !deterministic)
    std::fprintf(report_stream(), "exact per-walk variance (%.6g, %.6g, %.6g), sample (%.6g, %.6g, %.6g)\n", est.var_theory(0),
                est.var_theory(1), est.var_theory(2), est.var(0), est.var(1), est.var(2));
  if (command.theory && !deterministic && !est.var_theory.allFinite())
    warn(summary, command.method + ": the exact per-walk variance is infinite (its second-moment system does not "
                  "converge), so the standard error is meaningless although the estimate is unbiased" +
                  std::string(importance ? "; use a better importance (more --importance-sweeps) or a larger "
                                           "--defensive" : "; choose another --survival"));
  summary.json()["measurement"] = measurement_json(measurement, response, command.theory);
  if (!command.scene.json.empty()) summary.write(command.scene.json);
  return 0;
}

}  // namespace radwalk::app
