#include "apps/measure_response.h"

#include <cmath>

#include "core/error.h"
#include "formfactor/form_factor_noise.h"
#include "solve/discretisation_error.h"
#include "solve/form_factor_error.h"
#include "solve/solve_radiosity.h"
#include "visibility/embree_visibility.h"

#include <cmath>

#include "pathtrace/camera_response.h"
#include "solve/response_spec.h"
#include "visibility/embree_visibility.h"

namespace radwalk::app {

Response camera_measure_response(const SceneCamera& fitted, int width, int height, const Visibility& visibility,
                                 const PatchSet& patches) {
  const PinholeCamera camera(fitted.camera, width, height);
  const CameraResponse cr = camera_response(camera, visibility, patches, 4);
  Response response{cr.R, "the camera view (" + std::to_string(width) + " x " + std::to_string(height) +
                              " pixels, 4 x 4 film points each; M = mean pixel radiance)"};
  check_response(response, patches.size());
  return response;
}

Response measure_response(const std::string& spec, const std::string& scene, const PatchSet& patches,
                          const std::vector<std::int32_t>& group_of_patch, const std::vector<std::string>& groups,
                          const std::vector<double>& camera_option, int width, int height, SceneCamera* fitted) {
  if (spec != "camera") return parse_response(spec, patches, group_of_patch, groups, scene);
  const EmbreeVisibility visibility(patches);
  const SceneCamera camera = fit_scene_camera(scene, patches, camera_option, &visibility);
  if (fitted) *fitted = camera;
  return camera_measure_response(camera, width, height, visibility, patches);
}

nlohmann::json measurement_json(const Measurement& m, const Response& response, bool theory) {
  const MeasureEstimate& est = m.estimate;
  const auto rgb = [](const Rgb& v) {
    nlohmann::json a = nlohmann::json::array();
    for (int c = 0; c < 3; ++c) a.push_back(std::isfinite(v(c)) ? nlohmann::json(v(c)) : nlohmann::json());
    return a;
  };
  nlohmann::json j = {{"method", est.method}, {"response", response.what}, {"M", rgb(est.M)}, {"seconds", est.seconds}};
  // M_se: the walks' noise and, for form factors traced here, theirs (apps/cmd_measure.cpp).
  if (!m.deterministic || (est.se > 0).any()) j["M_se"] = rgb(est.se);
  if (!m.deterministic) {
    j["var_per_walk"] = rgb(est.var);
    j["walks_total"] = est.walks;
    j["steps"] = est.counters.steps;
    if (est.var_theory.allFinite() || theory) j["var_per_walk_theory"] = rgb(est.var_theory);
  }
  return j;
}

PatchRgb discrete_solution(const PatchSet& patches, const RadiosityProblem& problem) {
  SolveOptions o;
  o.tol = 1e-4;
  o.max_iterations = default_max_iterations(o.solver, patches.size());
  const Solution b = solve_radiosity(problem, o);
  if (b.B.rows() != static_cast<Eigen::Index>(patches.size()))
    throw InputError("error estimate: the radiosity for the measurement's error could not be solved: " + b.message);
  return b.B;
}

nlohmann::json measurement_total_error(const Rgb& M_se, const Rgb& M_disc, Rgb& total) {
  for (int c = 0; c < 3; ++c) total(c) = std::hypot(M_se(c), M_disc(c));
  return {{"M_err", {total(0), total(1), total(2)}}, {"combination", "M_err = sqrt(M_se^2 + M_disc^2)"}};
}

nlohmann::json add_measurement_discretisation_error(const PatchSet& patches, const RadiosityProblem& problem,
                                                    const PatchRgb& B, const Response& response, int directions,
                                                    std::uint64_t seed, Rgb& M_disc, double& seconds) {
  if (directions <= 0) return nullptr;
  const EmbreeVisibility visibility(patches);
  const Eigen::VectorXd W = problem.area.cwiseProduct(response.R);
  const MeasurementDiscretisationError e =
      measurement_discretisation_error(patches, visibility, problem, B, W, directions, seed);
  M_disc = e.standard_error;
  seconds = e.seconds;
  return {{"M_disc", {e.standard_error(0), e.standard_error(1), e.standard_error(2)}},
          {"estimate", {e.estimate(0), e.estimate(1), e.estimate(2)}},
          {"directions_per_point", directions},
          {"rays", e.rays},
          {"adjoint_sweeps", e.sweeps},
          {"method", "eps = sum_j Psi_j d_j with the adjoint Psi = (I - H)^-T A R and the within-patch fluctuation "
                     "source d; M_disc = sqrt(eps^2 + Var(eps)) (docs/theory/discretisation_error.md)"}};
}

nlohmann::json add_form_factor_error(const PatchSet& patches, const FormFactors& ff, const RadiosityProblem& problem,
                                     const PatchRgb& B, const Response& response, Measurement& measurement,
                                     std::string& covers) {
  nlohmann::json j;
  if (!has_noise_model(ff)) {
    const bool analytic = !ff.row_std_error.empty();
    j["form_factors"] = analytic ? "not included: the analytic form factors' visibility noise is not propagated"
                                 : "not included: F was read from a file, which does not record how it was sampled";
    covers = analytic ? ", without the analytic form factors' visibility noise"
                      : ", without the noise of the form factors read from the file";
    return j;
  }
  const EmbreeVisibility visibility(patches);
  const Eigen::VectorXd W = problem.area.cwiseProduct(response.R);
  const MeasurementError e = measurement_form_factor_error(patches, visibility, ff, problem, B, W);
  MeasureEstimate& est = measurement.estimate;
  const Rgb walks_se = est.se;
  const Rgb& F_se = e.standard_error;
  // sqrt(walks^2 + F^2) without squaring values near the largest double.
  const Rgb larger = walks_se.max(F_se);
  est.se = (larger > 0).select(larger * ((walks_se.min(F_se) / larger).square() + 1.0).sqrt(), Rgb::Zero());
  j["form_factors_M_se"] = {F_se(0), F_se(1), F_se(2)};
  j["walks_M_se"] = {walks_se(0), walks_se(1), walks_se(2)};
  j["sampling_factor_rays"] = e.calibration.factors.rays;
  j["sampling_factor_emitter"] = e.calibration.factors.emitter;
  j["calibration_rows"] = e.calibration.rows;
  j["calibration_replicates"] = e.calibration.replicates;
  j["adjoint_sweeps"] = e.sweeps;
  j["method"] = "first-order propagation of each row's gather variance through the adjoint: Var(M) = "
                "sum_j (Psi_j rho_j)^2 V_j (docs/theory/error_estimate.md)";
  covers = ", with the form factors' noise";
  return j;
}


}  // namespace radwalk::app
