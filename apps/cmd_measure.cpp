// radwalk measure SCENE --response SPEC [--method M]: one measurement M = <R, B>_A = sum_i A_i R_i B_i with its
// standard error (solve/measurement.h, walk/measure_walks.h, walk/importance_walk.h).
#include <cstdio>
#include <string>

#include "apps/measure_response.h"
#include "apps/options.h"
#include "apps/pipeline.h"
#include "apps/scene_camera.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/timer.h"
#include "pathtrace/camera_response.h"
#include "solve/direct_solver.h"
#include "solve/measurement.h"
#include "visibility/embree_visibility.h"
#include "walk/measure_walks.h"
#include "walk/walk_variance.h"

namespace radwalk::app {
namespace {

nlohmann::json rgb_json(const Rgb& v) { return {v(0), v(1), v(2)}; }

}  // namespace

int run_measure(const MeasureCommand& command) {
  RunSummary summary("measure", command.scene.argv);
  Mesh mesh;
  const PatchSet patches = load_patches(command.scene, summary, mesh);
  Response response;
  if (command.response == "camera") {
    // R_i = f_i / (pi A_i), f_i the film fraction seeing patch i: M is the image's mean pixel radiance.
    const Camera cam = scene_camera(command.scene.scene, patches, command.camera);
    const PinholeCamera camera(cam, command.width, command.height);
    const EmbreeVisibility visibility(patches);
    const CameraResponse cr = camera_response(camera, visibility, patches, 4);
    response = {cr.R, "the camera view (" + std::to_string(command.width) + " x " + std::to_string(command.height) +
                          " pixels, 4 x 4 film points each; M = mean pixel radiance)"};
    check_response(response, patches.size());
    summary.json()["camera"] = {{"position", {cam.position(0), cam.position(1), cam.position(2)}},
                                {"direction", {cam.direction(0), cam.direction(1), cam.direction(2)}},
                                {"up", {cam.up(0), cam.up(1), cam.up(2)}},
                                {"vfov_deg", cam.vfov * 180.0 / kPi},
                                {"width", command.width},
                                {"height", command.height}};
  } else {
    response = parse_response(command.response, mesh, patches);
  }
  const bool importance = command.method == "importance-gather" || command.method == "importance-shoot";
  const bool deterministic = command.method == "direct" || command.method == "adjoint-direct";
  WalkOptions walk = command.walk;
  walk.seed = command.scene.seed;
  if (!deterministic && !importance) {
    walk.method = parse_walk_method(command.method);
    walk.walks_per_patch = walk.particles = command.walks;
    check_walk_options(walk, patches.size());
  }
  // The LU solves (direct, adjoint-direct, the exact importance) are for scenes the dense LU handles; above, a
  // sparse LU of a form-factor matrix fills in (solve/direct_solver.h) and takes minutes to hours: refused
  // before any form factor is traced.
  const bool needs_lu = deterministic || (importance && command.importance_sweeps < 0);
  if (needs_lu && patches.size() > static_cast<std::size_t>(kDenseMaxPatches))
    throw InputError("--method " + command.method +
                     (importance ? " with the exact importance" : "") + " needs an LU of " +
                     std::to_string(patches.size()) + " patches (at most " + std::to_string(kDenseMaxPatches) +
                     "): use a walk method (e.g. --method gather-expected-value --kernel ray, no F stored) or " +
                     (importance ? "--importance-sweeps K" : "importance walks with --importance-sweeps K"));
  ThreadLimit limit(command.scene.threads);
  const bool ray = !deterministic && !importance && walk.kernel == WalkKernel::ray;

  MeasureEstimate est;
  est.method = command.method;
  const auto n = static_cast<Eigen::Index>(patches.size());
  if (ray) {
    const RadiosityProblem problem = make_problem(patches, SparseF(n, n));
    const EmbreeVisibility visibility(patches);
    est = measure_random_walk(problem, &patches, &visibility, walk, response, command.walks, false);
  } else {
    FormFactors ff = obtain_form_factors(command.scene, command.ff, patches, summary);
    const RadiosityProblem problem = make_problem(patches, std::move(ff.F));
    Timer timer;
    if (command.method == "direct") {
      const DirectSolver solver(problem);
      const Solution s = solver.solve(problem);
      if (s.status != SolveStatus::converged) throw NumericalError(s.message);
      est.M = measure(problem.area, response.R, s.B);
      est.se = est.var = Rgb::Zero();
    } else if (command.method == "adjoint-direct") {
      const Solution Y = solve_adjoint_direct(problem, response);
      if (Y.status != SolveStatus::converged) throw NumericalError(Y.message);
      est.M = adjoint_measure(problem.area, Y.B, problem.E);
      est.se = est.var = Rgb::Zero();
    } else if (importance) {
      const bool sensor = command.method == "importance-gather";
      const bool exact = command.importance_sweeps < 0;
      PatchRgb g;
      if (exact) {
        if (sensor) {
          const Solution s = DirectSolver(problem).solve(problem);
          if (s.status != SolveStatus::converged) throw NumericalError(s.message);
          g = s.B;
        } else {
          const Solution Y = solve_adjoint_direct(problem, response);
          if (Y.status != SolveStatus::converged) throw NumericalError(Y.message);
          g = Y.B;
        }
      } else {
        g = sensor ? partial_radiosity(problem, command.importance_sweeps)
                   : partial_importance(problem, response, command.importance_sweeps);
      }
      const double alpha = command.defensive >= 0 ? command.defensive : exact ? 0.0 : 0.1;
      est = measure_importance(problem, response,
                               sensor ? ImportanceDirection::from_sensor : ImportanceDirection::from_sources, g, alpha,
                               command.walks, walk.seed, command.theory);
      summary.json()["importance"] = {{"source", exact ? "direct" : "jacobi"},
                                      {"sweeps", command.importance_sweeps},
                                      {"defensive", alpha}};
    } else {
      est = measure_random_walk(problem, nullptr, nullptr, walk, response, command.walks, command.theory);
    }
    if (deterministic) est.seconds = timer.seconds();
  }
  summary.add_timing("measure", est.seconds);

  std::printf("%s: M = <R, B>_A over %s = (%.9g, %.9g, %.9g)", command.method.c_str(), response.what.c_str(),
              est.M(0), est.M(1), est.M(2));
  if (!deterministic)
    std::printf(" +- (%.3g, %.3g, %.3g) (standard error, %ld walks)", est.se(0), est.se(1), est.se(2), est.walks);
  std::printf(", %.3f s\n", est.seconds);
  if (command.theory && !deterministic)
    std::printf("exact per-walk variance (%.6g, %.6g, %.6g), sample (%.6g, %.6g, %.6g)\n", est.var_theory(0),
                est.var_theory(1), est.var_theory(2), est.var(0), est.var(1), est.var(2));
  if (command.theory && !deterministic && !est.var_theory.allFinite())
    warn(summary, command.method + ": the exact per-walk variance is infinite (its second-moment system does not "
                  "converge), so the standard error is meaningless although the estimate is unbiased" +
                  std::string(importance ? "; use a better importance (more --importance-sweeps) or a larger "
                                           "--defensive" : "; choose another --survival"));
  nlohmann::json& j = summary.json()["measurement"];
  j = {{"method", command.method}, {"response", response.what}, {"M", rgb_json(est.M)},
       {"seconds", est.seconds}};
  if (!deterministic) {
    j["se"] = rgb_json(est.se);
    j["var_per_walk"] = rgb_json(est.var);
    j["walks"] = est.walks;
    j["steps"] = est.counters.steps;
    if (est.var_theory.allFinite() || command.theory) j["var_theory"] = rgb_json(est.var_theory);
  }
  if (!command.scene.json.empty()) summary.write(command.scene.json);
  return 0;
}

}  // namespace radwalk::app
