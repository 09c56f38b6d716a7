// radwalk solve SCENE [--solver ...] [-o B.vtp] [--csv] [--json]: radiosity of every patch.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <optional>

#include "apps/finite_outputs.h"
#include "apps/options.h"
#include "apps/pipeline.h"
#include "apps/power_balance.h"
#include "apps/progressive_series.h"
#include "apps/discretisation_error.h"
#include "apps/run_metadata.h"
#include "apps/statistical_error.h"
#include "apps/hierarchical_target_error.h"
#include "apps/target_error.h"
#include "core/error.h"
#include "core/parallel.h"
#include "hierarchy/estimate_refinement.h"
#include "hierarchy/hierarchical_jacobi.h"
#include "hierarchy/leaf_patches.h"
#include "solve/adaptive_refinement.h"
#include "solve/discretisation_error.h"
#include "solve/problem.h"
#include "solve/residual.h"
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

SolveOptions solve_options(const SolveCommand& c, std::size_t patches) {
  SolveOptions o;
  o.solver = c.solver;
  o.tol = c.tol;
  o.max_iterations = c.max_iterations > 0 ? c.max_iterations : default_max_iterations(c.solver, patches);
  return o;
}

// One-line refusals of option combinations that cannot work.
void check_combinations(const SolveCommand& c) {
  if (c.target_error > 0 && c.refine > 0)
    throw InputError("--target-error and --refine cannot be combined: --target-error splits patches itself, where "
                     "its discretisation estimate says");
  if (c.hierarchical) {
    if (c.solver != "auto")
      throw InputError("--hierarchical is a solver of its own (hierarchical stochastic Jacobi); it cannot take --solver " +
                       c.solver);
    if (c.refine > 0)
      throw InputError("--hierarchical refines its element trees itself; it cannot be combined with --refine");
    if (!c.progressive.empty()) throw InputError("--hierarchical and --progressive cannot be combined");
    if (c.target_error <= 0 && c.hierarchical_refine == "estimate" && !(c.hierarchical_target > 0) && c.hierarchical_max_leaves <= 0)
      throw InputError("--hierarchical-refine estimate needs a stopping rule: --hierarchical-target E (the estimated "
                       "relative error) or --hierarchical-max-leaves N");
    if (c.hierarchical_clusters == "on" && c.hierarchical_refine == "estimate")
      throw InputError("--hierarchical-clusters on cannot be combined with --hierarchical-refine estimate: the "
                       "estimate that drives that refinement does not see the clusters' spreading error");
    const int side = static_cast<int>(std::lround(std::sqrt(static_cast<double>(c.hierarchical_points))));
    if (side * side != c.hierarchical_points)
      throw InputError("--hierarchical-points must be a square (1, 4, 9, 16, ...: a stratified grid); got " +
                       std::to_string(c.hierarchical_points));
  }
  if (c.refine > 0) {
    if (c.solver == "random-walk")
      throw InputError("--refine needs a deterministic solver (auto, direct, jacobi, gauss-seidel, southwell)");
    if (!c.ff.form_factors.empty())
      throw InputError("--refine estimates form factors for every refined mesh; it cannot use --form-factors");
    if (!c.progressive.empty()) throw InputError("--refine and --progressive cannot be combined");
  }
  if (!c.progressive.empty() && c.solver != "jacobi" && c.solver != "gauss-seidel" && c.solver != "southwell" &&
      c.solver != "random-walk")
    throw InputError("--progressive needs --solver jacobi, gauss-seidel, southwell or random-walk (got " + c.solver +
                     ")");
}

// Adaptive patching (solve_adaptive): each step on stderr and in the JSON summary under "refine".
RefinedSolution run_refinement(const SolveCommand& command, PatchSet patches, RunSummary& summary) {
  RefineOptions r;
  r.tol = command.refine;
  r.max_steps = command.refine_steps;
  r.max_patches = static_cast<std::size_t>(command.max_patches);
  r.noise_z = command.refine_noise;
  r.floor_fraction = command.refine_floor;
  // The first step goes through the shared stage (its notes and warnings, e.g. back hits, are the scene's); the
  // later ones estimate quietly, with the same options.
  int calls = 0;
  const FormFactorStage stage = [&](const PatchSet& p) {
    if (calls++ == 0) return obtain_form_factors(command.scene, command.ff, p, summary);
    return trace_form_factors(command.scene, command.ff, p);
  };
  const auto report = [](const RefineStep& s) {
    note("refine step " + std::to_string(s.step) + ": " + std::to_string(s.patches) + " patches, form factors " +
         std::to_string(s.form_factor_seconds) + " s, " + s.method + " " + std::to_string(s.solve_seconds) +
         " s, largest jump " + std::to_string(s.max_jump) + ", " + std::to_string(s.marked) + " marked, " +
         std::to_string(s.split) + " split");
  };
  const std::size_t initial = patches.size();
  RefinedSolution result =
      solve_adaptive(std::move(patches), stage, solve_options(command, command.max_patches), r, report);

  auto& j = summary.json()["refine"];
  j["tol"] = r.tol;
  j["max_steps"] = r.max_steps;
  j["max_patches"] = r.max_patches;
  j["floor_fraction"] = r.floor_fraction;
  j["noise_z"] = r.noise_z;
  j["criterion"] = "max over coplanar edge neighbours and channels of |H_i - H_j| / max(H_i, H_j, floor), "
                   "H = (B - E) / rho of the visible part; differences within noise_z form-factor standard errors ignored";
  j["initial_patches"] = initial;
  j["stop_reason"] = result.stop_reason;
  double ff_seconds = 0, solve_seconds = 0, refine_seconds = 0;
  for (const RefineStep& s : result.steps) {
    j["steps"].push_back(refine_step_json(s));
    ff_seconds += s.form_factor_seconds;
    solve_seconds += s.solve_seconds;
    refine_seconds += s.refine_seconds;
  }
  summary.add_timing("form_factors", ff_seconds);
  summary.add_timing("refine", refine_seconds);
  result.solution.seconds = solve_seconds;  // timed as "solve": all the steps' solves
  summary.json()["patches"] = result.patches.size();
  summary.json()["form_factor_nonzeros"] = result.form_factors.F.nonZeros();
  note("refinement stopped (" + result.stop_reason + ") after " + std::to_string(result.steps.size()) +
       " solves: " + std::to_string(initial) + " -> " + std::to_string(result.patches.size()) + " patches");
  return result;
}

// The random-walk solve; with --progressive also its convergence series (progressive_series.h) over the walk count
// of the method's direction (walks per patch, or particles).
Solution run_walks(const SolveCommand& command, const WalkOptions& walk, const RadiosityProblem& problem,
                   const PatchSet& patches, const Visibility* visibility, RunSummary& summary) {
  const bool gathering = is_gathering(walk.method);
  const long count = gathering ? walk.walks_per_patch : walk.particles;
  const auto walks = [&](long n) {
    WalkOptions w = walk;
    (gathering ? w.walks_per_patch : w.particles) = n;
    return solve_random_walk(problem, &patches, visibility, w);
  };
  Solution solution = walks(count);
  if (!command.progressive.empty())
    write_convergence_series(command.progressive, "solve.pvd", command.scene.scene, patches, count, solution, walks,
                             summary);
  return solution;
}

// The hierarchical solve (hierarchy/hierarchical_jacobi.h) on the element trees of `roots`; returns the leaves as
// the PatchSet of the outputs and records the "hierarchy" block of the JSON summary.
PatchSet run_hierarchical(const SolveCommand& command, const PatchSet& roots, Solution& solution,
                          RunSummary& summary) {
  HierarchicalOptions h;
  h.tol = command.hierarchical_tol;
  h.max_level = command.hierarchical_levels;
  h.min_area = command.hierarchical_min_area;
  h.points_side = static_cast<int>(std::lround(std::sqrt(static_cast<double>(command.hierarchical_points))));
  h.particles = command.hierarchical_rays;
  h.replicates = command.hierarchical_replicates;
  h.seed = command.scene.seed;
  h.clusters = command.hierarchical_clusters == "on";
  h.cluster_ratio = command.hierarchical_cluster_ratio;
  const EmbreeVisibility visibility(roots);
  const bool by_estimate = command.hierarchical_refine == "estimate";
  std::vector<EstimateRefinementStep> steps;
  bool reached = false;
  HierarchicalResult r;
  if (by_estimate) {
    h.direct_oracle = h.transport_oracle = false;
    EstimateRefinementOptions e;
    e.steps = command.hierarchical_steps;
    e.target = command.hierarchical_target;
    e.max_leaves = command.hierarchical_max_leaves;
    e.split_share = 0.8;
    e.rays_per_leaf = 300;
    EstimateRefinementResult er = refine_by_estimate(roots, visibility, h, e);
    r = std::move(er.solution);
    steps = std::move(er.steps);
    reached = er.reached;
  } else {
    r = solve_hierarchical(roots, visibility, h);
  }
  solution.method = "hierarchical-jacobi";
  solution.status = SolveStatus::converged;
  solution.message = "unshot power below 1e-6 of the first shot's, or 200 iterations per replicate";
  solution.B = r.B;
  solution.B_se = r.B_se;
  solution.var = r.var;
  solution.walks = r.rays;
  solution.iterations = r.iterations;
  solution.seconds = r.seconds;
  solution.info["shadow_rays"] = static_cast<double>(r.shadow_rays);
  solution.info["replicates"] = h.replicates;
  auto& j = summary.json()["hierarchy"];
  j["roots"] = roots.size();
  j["elements"] = r.tree.size();
  j["leaves"] = r.leaves.size();
  j["links"] = 0;     // per-ray level choice: no links are stored
  j["clusters"] = r.clusters;  // cluster nodes (hierarchy/cluster_tree.h); 0 with --hierarchical-clusters off
  j["cluster_deposits"] = r.cluster_deposits;
  if (h.clusters) j["cluster_ratio"] = h.cluster_ratio;
  j["memory_bytes"] = r.memory_bytes;
  j["levels"] = r.tree.depth() + 1;
  j["refinement_steps"] = {{"direct", r.direct_splits}, {"transport", r.transport_splits}};
  j["tol"] = h.tol;
  j["epsilon"] = r.epsilon;
  j["max_level"] = h.max_level;
  j["min_area"] = h.min_area;
  j["points"] = h.points_side * h.points_side;
  j["rays"] = r.rays;
  j["shadow_rays"] = r.shadow_rays;
  j["replicates"] = h.replicates;
  j["iterations"] = r.iterations;
  j["refine"] = command.hierarchical_refine;
  if (by_estimate) {
    nlohmann::json js = nlohmann::json::array();
    for (const EstimateRefinementStep& st : steps) {
      nlohmann::json x = {{"leaves", st.leaves}, {"split", st.split}, {"rays", st.rays}, {"seconds", st.seconds}};
      x["eta"] = std::isfinite(st.eta) ? nlohmann::json(st.eta) : nlohmann::json(nullptr);
      js.push_back(x);
    }
    j["estimate_steps"] = js;
    j["target"] = command.hierarchical_target;
    j["max_leaves"] = command.hierarchical_max_leaves;
    j["target_reached"] = reached;
    for (const EstimateRefinementStep& st : steps)
      note("hierarchical, refined by the estimate: " + std::to_string(st.leaves) + " leaves" +
           (std::isfinite(st.eta) ? ", estimated relative error " + std::to_string(st.eta) : std::string()) +
           (st.split > 0 ? ", " + std::to_string(st.split) + " split" : std::string()));
  }
  note("hierarchical: " + std::to_string(roots.size()) + " patches -> " + std::to_string(r.tree.size()) +
       " elements, " + std::to_string(r.leaves.size()) + " leaves, " + std::to_string(r.tree.depth() + 1) +
       " levels (" + std::to_string(r.direct_splits) + " splits by the direct light, " +
       std::to_string(r.transport_splits) + " by the transport oracle)");
  if (h.clusters)
    note("hierarchical clusters: " + std::to_string(r.clusters) + " clusters received " +
         std::to_string(r.cluster_deposits) + " of " + std::to_string(r.rays) +
         " rays (their spreading error is in neither B_se nor B_disc: docs/hierarchy.md, Clusters)");
  return leaf_patches(roots, r.tree, r.leaves);
}

}  // namespace

int run_solve(const SolveCommand& command) {
  RunSummary summary("solve", command.scene.argv);
  check_combinations(command);
  SceneOptions scene = command.scene;
  scene.splits_later = command.target_error > 0;  // --target-error splits the patches itself
  PatchSet patches = load_patches(scene, summary);
  // The walk options are checked here, once, before any form factor is traced.
  const bool walks = command.solver == "random-walk";
  WalkOptions walk = command.walk;
  walk.seed = command.scene.seed;
  walk.progress = true;
  if (walks) check_walk_options(walk, patches.size());
  warn_non_diffuse(patches, summary);
  ThreadLimit limit(command.scene.threads);

  const bool ray_walk = walks && walk.kernel == WalkKernel::ray;
  std::vector<CellField> fields;
  // The form-factor diagnostics (a transpose of F and a pass over it) only when a per-patch file is written.
  const bool per_patch_output = !command.scene.vtp.empty() || !command.scene.csv.empty();
  Solution solution;
  std::string error_line;  // the estimated error, printed after the solver's line
  RayFates fates;  // where the rays leaving each patch went (power_balance.h)
  GroupNoiseModel noise;  // B_se's model, for the materials' means (add_statistical_error)
  // The discretisation error and the total after the statistical line (apps/discretisation_error.h).
  const auto add_discretisation = [&](const RadiosityProblem& problem) {
    if (solution.status == SolveStatus::refused) return;
    const std::string line = add_discretisation_error(patches, problem, solution, summary,
                                                      command.discretisation_directions, command.scene.seed, noise);
    if (!line.empty()) error_line += (error_line.empty() ? "" : "\n") + line;
  };
  std::optional<TargetErrorRun> target;
  if (command.target_error > 0) {
    target = command.hierarchical ? run_hierarchical_target_error(command, patches, summary)
                                  : run_target_error(command, std::move(patches), summary);
    TargetErrorResult& r = target->result;
    patches = std::move(r.patches);
    if (command.hierarchical && command.hierarchical_transport == "rays") {
      fates = trace_ray_fates(patches, command.scene.seed);  // no form factors: the fates' own rays
    } else {
      fates = {r.form_factors.rays, r.form_factors.escaped, r.form_factors.back_hits};
      if (per_patch_output) fields = form_factor_fields(r.form_factors, patches);
    }
    solution = std::move(r.solution);
    error_line = target->error_line;
  } else if (command.refine > 0) {
    RefinedSolution refined = run_refinement(command, std::move(patches), summary);
    patches = std::move(refined.patches);
    fates = {refined.form_factors.rays, refined.form_factors.escaped, refined.form_factors.back_hits};
    if (per_patch_output) fields = form_factor_fields(refined.form_factors, patches);
    fields.push_back(scalar_field("jump", refined.jump));
    solution = std::move(refined.solution);
  } else if (command.hierarchical) {
    patches = run_hierarchical(command, patches, solution, summary);
    const auto n = static_cast<Eigen::Index>(patches.size());
    const RadiosityProblem problem = make_problem(patches, SparseF(n, n));
    fates = trace_ray_fates(patches, command.scene.seed);
    summary.json()["patches"] = patches.size();
    add_discretisation(problem);
  } else if (ray_walk) {
    // The ray kernel traces every step: no form factors are stored (memory O(N)).
    const auto n = static_cast<Eigen::Index>(patches.size());
    const RadiosityProblem problem = make_problem(patches, SparseF(n, n));
    const EmbreeVisibility visibility(patches);
    solution = run_walks(command, walk, problem, patches, &visibility, summary);
    fates = trace_ray_fates(patches, command.scene.seed);
    add_discretisation(problem);
  } else {
    // Over MPI the deterministic solvers take a row-distributed F (each rank its rows: Jacobi and Gauss-Seidel
    // sweep them, the direct solve and Southwell gather the whole F); the matrix-kernel walks need every row.
    FormFactors ff = obtain_form_factors(command.scene, command.ff, patches, summary,
                                         walks ? RowsHeld::every_row : RowsHeld::own_rows);
    if (per_patch_output) fields = form_factor_fields(ff, patches);
    fates = {ff.rays, ff.escaped, ff.back_hits};
    const RadiosityProblem problem = make_problem(patches, std::move(ff.F), std::move(ff.row_blocks));
    if (walks) {
      solution = run_walks(command, walk, problem, patches, nullptr, summary);
      error_line = add_statistical_error(patches, ff, problem, solution, summary, &noise);
      add_discretisation(problem);
    } else {
      SolveOptions o = solve_options(command, patches.size());
      std::optional<ProgressiveSeries> series;
      if (!command.progressive.empty()) {
        VtpMetadata m;
        m.set_text("run_id", run_id_of(summary));
        m.set_text("method", command.solver);
        m.set_text("scene", command.scene.scene);
        series.emplace(command.progressive, patches,
                       [&problem](const PatchRgb& B) { return relative_residual(problem, B); }, m);
        o.on_iterate = [&](long iteration, const PatchRgb& B) { series->add(iteration, B); };
        // Southwell: a frame every tenth of a sweep's worth of shots (the series thins itself to 200 steps).
        o.iterate_every = std::max(1L, static_cast<long>(patches.size()) / 10);
      }
      solution = solve_radiosity(problem, o);
      if (solution.status != SolveStatus::refused)
        error_line = add_statistical_error(patches, ff, problem, solution, summary, &noise);
      add_discretisation(problem);
      if (series) {
        const std::size_t steps = series->finish();
        summary.json()["progressive"] = {{"pvd", series->pvd_path()}, {"steps", steps}, {"stride", series->stride()}};
        note("wrote " + series->pvd_path() + " (" + std::to_string(steps) + " steps)");
      }
    }
  }
  summary.add_timing("solve", solution.seconds);
  refuse_overflow(solution, "solve", patches.max_emission());
  if (walks && too_few_particles(solution))
    warn(summary, solution.method + ": " + std::to_string(static_cast<long>(solution.info.at("unreached_patches"))) +
                      " of the " + std::to_string(static_cast<long>(solution.info.at("reflecting_patches"))) +
                      " non-emitting reflecting patches got no particle's score, so their B = 0 is an artefact of " +
                      std::to_string(walk.particles) + " particles: use more --particles");

  // Report: method, status, cost, accuracy.
  std::fprintf(report_stream(), "%s: %s (%s)", solution.method.c_str(), to_string(solution.status), solution.message.c_str());
  if (solution.iterations > 0) std::fprintf(report_stream(), ", %ld iterations", solution.iterations);
  if (solution.walks > 0) std::fprintf(report_stream(), ", %ld walks, %ld steps", solution.walks, solution.steps);
  if (solution.residual == solution.residual) std::fprintf(report_stream(), ", relative residual %.3g", solution.residual);
  std::fprintf(report_stream(), ", %.3f s\n", solution.seconds);
  summary.json()["solution"] = solution_json(solution);
  auto& j = summary.json()["solution"];

  if (solution.B.rows() == static_cast<Eigen::Index>(patches.size())) {
    // Area-weighted mean radiosity per channel, a quick sanity figure; when sum A_i B_i overflows (B near the
    // largest double), with the weights A_i / total area, whose sum stays finite whenever B is.
    Rgb mean = Rgb::Zero();
    for (std::size_t i = 0; i < patches.size(); ++i)
      mean += patches.area[i] * solution.B.row(static_cast<Eigen::Index>(i)).transpose();
    mean /= patches.total_area();
    if (!mean.isFinite().all() && solution.B.allFinite()) {
      mean = Rgb::Zero();
      for (std::size_t i = 0; i < patches.size(); ++i)
        mean += (patches.area[i] / patches.total_area()) * solution.B.row(static_cast<Eigen::Index>(i)).transpose();
    }
    std::fprintf(report_stream(), "area-weighted mean B = (%.6g, %.6g, %.6g) %s\n", mean[0], mean[1], mean[2],
                 length_unit(command.scene).radiosity().c_str());
    if (!error_line.empty()) std::fprintf(report_stream(), "%s\n", error_line.c_str());
    j["mean_B"] = {mean[0], mean[1], mean[2]};
    report_power_balance(patches, solution.B, solution.B_se, fates, summary);
    fields.push_back(rgb_field("B", solution.B));
    if (solution.B_se.size()) fields.push_back(rgb_field("B_se", solution.B_se));
    if (solution.B_disc.size()) {
      fields.push_back(rgb_field("B_disc", solution.B_disc));
      fields.push_back(rgb_field("B_err", total_error(solution.B_se, solution.B_disc)));
    }
    // ParaView names B_var, B_var_theory (`var` is reserved in its Calculator); the CSV keeps var_*, var_theory_*.
    if (solution.var.size()) fields.push_back(with_csv_name(rgb_field("B_var", solution.var), "var"));
    if (solution.var_theory.size())
      fields.push_back(with_csv_name(rgb_field("B_var_theory", solution.var_theory), "var_theory"));
    VtpMetadata metadata = solution_metadata(solution, patches);
    metadata.set_text("solver", command.hierarchical ? "hierarchical" : command.solver);
    if (command.hierarchical && target) {
      metadata.set_integer("rays_per_leaf", target->result.steps.back().rays_per_patch);
      metadata.set_text("hierarchical_transport", command.hierarchical_transport);
    } else if (command.hierarchical) {
      metadata.set_real("hierarchical_tol", command.hierarchical_tol);
      metadata.set_integer("rays", command.hierarchical_rays);
    } else if (command.solver == "random-walk") {
      const WalkMethodRow& row = method_row(walk.method);
      metadata.set_text("walk", std::string(direction_name(row.direction)));
      metadata.set_text("estimator", std::string(row.estimator));
      metadata.set_text("kernel", std::string(kernel_name(walk.kernel)));
      metadata.set_text("survival", std::string(survival_name(walk.survival.rule)));
      if (is_gathering(walk.method))
        metadata.set_integer("walks_per_patch", walk.walks_per_patch);
      else
        metadata.set_integer("particles", walk.particles);
    } else {
      metadata.set_real("tol", command.tol);
    }
    if (command.refine > 0) metadata.set_real("refine_tol", command.refine);
    if (target) metadata.set_real("target_error", command.target_error);
    write_outputs(command.scene, patches, fields, summary, metadata);
  } else if (!command.scene.json.empty()) {
    summary.write(command.scene.json);
  }
  if (target && solution.status == SolveStatus::converged && !target->result.reached) {
    const TargetErrorStep& last = target->result.steps.back();
    std::fprintf(stderr,
                 "radwalk: target error %s not reached (%s stopped it after %zu steps): the answer written has an "
                 "estimated error of %s with %zu %s and %ld rays a %s%s\n",
                 percent(command.target_error).c_str(), target->result.stop_reason.c_str(), target->result.steps.size(),
                 percent(last.total).c_str(), last.patches, command.hierarchical ? "leaves" : "patches",
                 last.rays_per_patch, command.hierarchical ? "leaf" : "patch",
                 !command.hierarchical ? "; the default route (without --target-route uniform) splits elements only "
                                         "where the estimate asks (docs/accuracy.md, \"Where the uniform route fails\")"
                 : target->result.stop_reason == "depth"
                     ? "; no leaf it would split is above --hierarchical-levels and of at least 4 x "
                       "--hierarchical-min-area"
                     : "");
    return 1;
  }
  if (solution.status == SolveStatus::converged) return 0;
  std::fprintf(stderr, "radwalk: %s did not converge: %s\n", solution.method.c_str(), solution.message.c_str());
  return solution.status == SolveStatus::max_iterations ? 1 : 3;
}

}  // namespace radwalk::app
