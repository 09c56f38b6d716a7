// radwalk solve SCENE [--solver ...] [-o B.vtp] [--csv] [--json]: radiosity of every patch.
#include <cstdio>

#include "apps/options.h"
#include "apps/pipeline.h"
#include "core/error.h"
#include "core/parallel.h"
#include "solve/problem.h"
#include "solve/solve_radiosity.h"
#include "visibility/embree_visibility.h"
#include "walk/random_walk_solver.h"

namespace radwalk::app {
namespace {

void warn_non_diffuse(const PatchSet& patches, RunSummary& summary) {
  for (const Material& m : patches.materials)
    if (m.kind != BsdfKind::diffuse) {
      warn(summary, "material '" + m.name + "' is not diffuse; the radiosity solvers treat it as Lambertian with "
                    "reflectance Kd (use 'radwalk pathtrace' for the non-diffuse materials)");
    }
}

WalkOptions walk_options(const SolveCommand& c) {
  WalkOptions w;
  w.walk = c.walk;
  w.estimator = c.estimator;
  w.kernel = c.kernel;
  w.walks = c.walks;
  w.seed = c.scene.seed;
  w.patches = c.patches;
  w.survival = c.survival;
  w.survival_constant = c.survival_constant;
  w.theory = c.theory;
  return w;
}

}  // namespace

int run_solve(const SolveCommand& command) {
  RunSummary summary("solve", command.scene.argv);
  const PatchSet patches = load_patches(command.scene, summary);
  warn_non_diffuse(patches, summary);
  ThreadLimit limit(command.scene.threads);

  const bool ray_walk = command.solver == "random-walk" && command.kernel == "ray";
  std::vector<CellField> fields = patch_fields(patches);
  Solution solution;
  if (ray_walk) {
    // The ray kernel traces every step: no form factors are stored (memory O(N)).
    const auto n = static_cast<Eigen::Index>(patches.size());
    const RadiosityProblem problem = make_problem(patches, SparseF(n, n));
    const EmbreeVisibility visibility(patches);
    solution = solve_random_walk(problem, &patches, &visibility, walk_options(command));
  } else {
    FormFactors ff = obtain_form_factors(command.scene, command.ff, patches, summary);
    const auto diagnostics = form_factor_fields(ff, patches);
    fields.insert(fields.end(), diagnostics.begin(), diagnostics.end());
    const RadiosityProblem problem = make_problem(patches, std::move(ff.F));
    if (command.solver == "random-walk") {
      solution = solve_random_walk(problem, &patches, nullptr, walk_options(command));
    } else {
      SolveOptions o;
      o.solver = command.solver;
      o.tol = command.tol;
      o.max_iterations = command.max_iterations > 0 ? command.max_iterations
                         : command.solver == "southwell"  ? 1000 * static_cast<long>(patches.size())
                                                          : 10000;
      solution = solve_radiosity(problem, o);
    }
  }
  summary.add_timing("solve", solution.seconds);

  // Report: method, status, cost, accuracy.
  std::printf("%s: %s (%s)", solution.method.c_str(), to_string(solution.status), solution.message.c_str());
  if (solution.iterations > 0) std::printf(", %ld iterations", solution.iterations);
  if (solution.walks > 0) std::printf(", %ld walks, %ld steps", solution.walks, solution.steps);
  if (solution.residual == solution.residual) std::printf(", relative residual %.3g", solution.residual);
  std::printf(", %.3f s\n", solution.seconds);
  auto& j = summary.json()["solution"];
  j["method"] = solution.method;
  j["status"] = to_string(solution.status);
  j["message"] = solution.message;
  j["iterations"] = solution.iterations;
  j["residual"] = solution.residual == solution.residual ? nlohmann::json(solution.residual) : nlohmann::json();
  j["residual_history"] = solution.residual_history;
  j["walks"] = solution.walks;
  j["steps"] = solution.steps;
  j["seconds"] = solution.seconds;
  for (const auto& [key, value] : solution.info) j["info"][key] = value;

  if (solution.B.rows() == static_cast<Eigen::Index>(patches.size())) {
    // Area-weighted mean radiosity per channel, a quick sanity figure.
    Rgb mean = Rgb::Zero();
    for (std::size_t i = 0; i < patches.size(); ++i)
      mean += patches.area[i] * solution.B.row(static_cast<Eigen::Index>(i)).transpose();
    mean /= patches.total_area();
    std::printf("area-weighted mean B = (%.6g, %.6g, %.6g) W/m^2\n", mean[0], mean[1], mean[2]);
    j["mean_B"] = {mean[0], mean[1], mean[2]};
    fields.push_back(rgb_field("B", solution.B));
    if (solution.B_se.size()) fields.push_back(rgb_field("B_se", solution.B_se));
    if (solution.var.size()) fields.push_back(rgb_field("var", solution.var));
    if (solution.var_theory.size()) fields.push_back(rgb_field("var_theory", solution.var_theory));
    write_outputs(command.scene, patches, fields, summary);
  } else if (!command.scene.json.empty()) {
    summary.write(command.scene.json);
  }
  if (solution.status == SolveStatus::converged) return 0;
  std::fprintf(stderr, "radwalk: %s did not converge: %s\n", solution.method.c_str(), solution.message.c_str());
  return solution.status == SolveStatus::max_iterations ? 1 : 3;
}

}  // namespace radwalk::app
