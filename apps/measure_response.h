#pragma once
// What `radwalk measure` shares with radwalk.measure (the Python module compiles this file as the CLI does):
// the response of a spec, `camera` (below) or any other by parse_response (solve/response_spec.h), and the JSON
// "measurement" object. The camera response lives in apps, beside scene_camera.h, because it joins the path
// tracer's camera_response with the solver's Response (no layer below apps has both).
#include <nlohmann/json.hpp>
#include <string>

#include "apps/scene_camera.h"
#include "mesh/mesh.h"
#include "formfactor/form_factors.h"
#include "patch/patch_set.h"
#include "solve/measurement.h"
#include "visibility/visibility.h"
#include "walk/measure_by_method.h"

namespace radwalk::app {

// R_i = f_i / (pi A_i), f_i the fraction of the film (width x height pixels, 4 x 4 film points each) that sees
// patch i (pathtrace/camera_response.h): M is the view's mean pixel radiance. check_response holds.
Response camera_measure_response(const SceneCamera& camera, int width, int height, const Visibility& visibility,
                                 const PatchSet& patches);

// The response of a spec: `camera` (the camera fitted as pathtrace's, fit_scene_camera with `camera_option`;
// it is stored in *fitted when given) or any spec of parse_response.
Response measure_response(const std::string& spec, const std::string& scene, const PatchSet& patches,
                          const std::vector<std::int32_t>& group_of_patch, const std::vector<std::string>& groups,
                          const std::vector<double>& camera_option, int width, int height,
                          SceneCamera* fitted = nullptr);

// The JSON "measurement" object (docs/json-schema.md): method, response (its words), M, seconds, and for the
// Monte Carlo methods M_se, var_per_walk, walks_total, steps and var_per_walk_theory (when finite or asked for
// with theory; null entries where infinite).
nlohmann::json measurement_json(const Measurement& measurement, const Response& response, bool theory);

// Adds the form factors' noise to the measurement's standard error (solve/form_factor_error.h; independent of the
// walks' own noise given F, so the variances add), for F as `ff` describes it (its F moved into `problem`).
// Returns the JSON's "error_estimate.statistical" object (the parts, the sampling factors, the adjoint's sweeps)
// and sets `covers` to what the printed standard error then covers (", with the form factors' noise", or that F
// read from a file or the analytic route's visibility noise is not included). B: the discrete solution (a few
// digits suffice; discrete_solution below).
nlohmann::json add_form_factor_error(const PatchSet& patches, const FormFactors& ff, const RadiosityProblem& problem,
                                     const PatchRgb& B, const Response& response, Measurement& measurement,
                                     std::string& covers);

// The discrete radiosity B of `problem` to a relative change of 1e-4, for the error estimates of a measurement
// (whose methods give M, not B). InputError when it cannot be solved.
PatchRgb discrete_solution(const PatchSet& patches, const RadiosityProblem& problem);

// M_err = sqrt(M_se^2 + M_disc^2) per channel (without squaring values near the largest double) into `total`;
// returns the JSON's "error_estimate.total" object.
nlohmann::json measurement_total_error(const Rgb& M_se, const Rgb& M_disc, Rgb& total);

// The estimated discretisation error of the measurement (solve/discretisation_error.h,
// measurement_discretisation_error) with `directions` per point (0: not estimated; returns null). Sets
// M_disc and the stage's seconds and returns the JSON's "error_estimate.discretisation" object.
nlohmann::json add_measurement_discretisation_error(const PatchSet& patches, const RadiosityProblem& problem,
                                                    const PatchRgb& B, const Response& response, int directions,
                                                    std::uint64_t seed, Rgb& M_disc, double& seconds);

}  // namespace radwalk::app
