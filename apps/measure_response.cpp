#include "apps/measure_response.h"

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
  if (!m.deterministic) {
    j["M_se"] = rgb(est.se);
    j["var_per_walk"] = rgb(est.var);
    j["walks_total"] = est.walks;
    j["steps"] = est.counters.steps;
    if (est.var_theory.allFinite() || theory) j["var_per_walk_theory"] = rgb(est.var_theory);
  }
  return j;
}

}  // namespace radwalk::app
