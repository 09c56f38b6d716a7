#pragma once
// Options of the radwalk commands, filled by the command-line parser (radwalk.cpp) and read by the commands.
// Options shared by several commands are spelled the same everywhere (see add_*_options in radwalk.cpp).
#include <cstdint>
#include <string>
#include <vector>

#include "apps/distinct_files.h"
#include "walk/walk_compare.h"
#include "walk/walk_options.h"

namespace radwalk::app {

// Every command that reads a scene.
struct SceneOptions {
  std::string scene;       // OBJ (+MTL), PLY, STL, glTF/GLB, .vtp/.vtk (mesh/read_scene.h)
  double max_edge = 0;     // split faces until no patch edge is longer than this; 0 keeps input faces
  double max_area = 0;     // --max-area: split faces until no patch area is above this; 0: no bound
  bool contact_cut = true;  // --contact-cut (default) / --no-contact-cut: cut faces along contacts when split (patch/contact.h)
  bool splits_later = false; // the command splits the patches itself (--target-error): --contact-cut cuts anyway
  int threads = 0;         // 0 = all cores
  std::uint64_t seed = 1;
  bool strict = false;     // --strict: refuse what the readers and validation would repair
  double scale = 1;        // --scale S: coordinates times S (mesh/length_unit.h)
  std::string orient = "outward";  // --orient none|consistent|outward (mesh/orient_shells.h)
  bool orient_given = false;  // --orient was given: it applies to a file of radwalk's patches too (mesh/validate.h)
  std::string open_shells = "auto";  // --open-shells auto|one-sided|two-sided (mesh/validate.h OpenShellSides)
  std::string unit;        // --unit mm|cm|m|in|ft: the unit of the file's coordinates ("" not given)
  std::vector<std::string> set_material;  // --set MATERIAL.Kd=r,g,b / MATERIAL.Ke=...: material overrides
  double rho_scale = 1;    // --rho-scale s: every Kd times s (after --set)
  bool two_sided = false;  // --two-sided: every (non-dielectric) material two-sided (patch/patch_set.h, add_back_sides)
  std::string vtp;         // -o FILE.vtp
  std::string csv;         // --csv FILE
  std::string json;        // --json FILE
  std::string paraview_state;  // --paraview-state FILE.py: ParaView state for the .vtp
  std::vector<std::string> argv;  // the command line, for the JSON summary
  std::vector<std::string> warnings;  // printed while reading the command line (ignored options), for the summary
  std::vector<NamedFile> outputs;     // every file the command writes (distinct_files.h), checked against inputs
  // For the run id (run_metadata.h): the command and its option values, canonical (radwalk.cpp), and the
  // --form-factors file of the commands that take one.
  std::string run_options;
  std::string form_factors_input;
};

// Commands that need form factors: estimate them, or read them from a Matrix Market file.
struct FormFactorCliOptions {
  long rays = 1000;            // rays per patch
  double rays_per_area = 0;    // if > 0: rays = max(min_rays, rays_per_area * area)
  long min_rays = 16;
  std::string form_factors;    // --form-factors F.mtx: read instead of estimating
  bool reciprocity = false;    // --reciprocity: average A_i F_ij and A_j F_ji
  bool enforce_closure = false;  // --enforce-closure: least-squares closure + reciprocity (formfactor/closure.h)
  bool sobol_rays = true;      // --sobol-rays / --no-sobol-rays: randomised Sobol cosine rays (FormFactorOptions::sobol)
  long emitter_samples = -1;   // --emitter-columns M: the emitter columns from M shadow samples per patch
                               // (formfactor/emitter_form_factors.h); 0: from the cosine rays; -1 (auto):
                               // choose_emitter_samples's choice
  bool analytic = false;       // --analytic: exact exchange areas x visibility (formfactor/analytic_form_factors.h)
  double analytic_cutoff = 0;     // --analytic-cutoff: pairs whose F bound is at most this are dropped (reported)
  long analytic_cutoff_rays = 0; // --analytic-cutoff-rays: cosine rays a row that estimate the dropped pairs instead
  long visibility_samples = 1024;  // --visibility-samples: at most this many point pairs per partly hidden pair
  bool normalise_rows = false;  // --normalise-rows: divide rows of a read F summing above 1 by their sums
};

struct PatchCommand {
  SceneOptions scene;
  std::string output;  // .vtp or .obj
};

struct FormFactorsCommand {
  SceneOptions scene;
  FormFactorCliOptions ff;
  std::string mtx;  // -o F.mtx
  std::string diagnostics_vtp;  // --vtp
};

struct SolveCommand {
  SceneOptions scene;
  FormFactorCliOptions ff;
  std::string solver = "auto";
  double tol = 1e-10;
  long max_iterations = 0;  // 0: 10000 sweeps, or 1000 x N shots for southwell
  // --solver random-walk: typed by the parser (walk/walk_method.h and walk_options.h name every choice) and
  // checked once the scene is loaded (check_walk_options), before any form factor is traced; the seed is
  // scene.seed.
  WalkOptions walk;
  // adaptive patching (solve_adaptive): --refine TOL > 0 turns it on
  double refine = 0;
  int refine_steps = 4;
  long max_patches = 20000;
  double refine_floor = 1;  // floor of the relative difference, as a fraction of the mean irradiance
  double refine_noise = 0;  // differences within this many form-factor standard errors do not split (0: off)
  // --target-error E (apps/target_error.h): steps of rays and patch splits until the estimated total error is at
  // most E; 0: off. The steps stop at max_patches or after max_seconds (0: no limit).
  double target_error = 0;
  double max_seconds = 0;
  // --target-route hierarchical|uniform: how --target-error refines. "hierarchical" (the default) splits the leaves
  // of an element tree per input face (hierarchy/hierarchical_target_error.h; it sets `hierarchical`, below, before
  // the options are checked); "uniform" splits the patches themselves (solve/target_error.h).
  std::string target_route = "hierarchical";
  // --target-each material|object|group|none: also each group's mean within E; "": the default, material
  // wherever the route can hold it (not the hierarchy's rays transport, which stores no F), else none.
  std::string target_each;
  int discretisation_directions = 16;  // --discretisation-directions L: directions per point of the discretisation
                                      // error estimate (solve/fluctuation_source.h); 0: not estimated
  // --hierarchical: hierarchical stochastic Jacobi on the element trees of the patches (hierarchy/hierarchical_jacobi.h)
  bool hierarchical = false;
  double hierarchical_tol = 1e-3;        // epsilon = tol x the emitted power (the refinement oracle's threshold)
  int hierarchical_levels = 8;           // deepest element level below a patch
  double hierarchical_min_area = 0;      // no element below this area (0: the levels alone bound the depth)
  int hierarchical_points = 16;          // points per element for the direct light and its oracle (a square)
  long hierarchical_rays = 1'000'000;    // rays of the indirect shooting in all
  int hierarchical_replicates = 4;       // independent replicates for the error bars
  // "oracle": the a-priori oracles refine (--hierarchical-tol); "estimate": solve, estimate each leaf's error, split
  // the largest, repeat (hierarchy/estimate_refinement.h) until --hierarchical-target or --hierarchical-max-leaves
  std::string hierarchical_refine = "oracle";
  double hierarchical_target = 0;        // estimate: stop once the estimated relative L2 error is at most this
  long hierarchical_max_leaves = 0;      // estimate: the budget of leaves (0: none)
  int hierarchical_steps = 12;           // estimate: splitting steps at most
  // oriented clusters of patches above the element trees (hierarchy/cluster_tree.h): "on" or "off"
  std::string hierarchical_clusters = "off";
  // --hierarchical --target-error: how each step's leaves are solved: "rays" (the hierarchical stochastic Jacobi)
  // or "form-factors" (the leaves as patches, the uniform route's traced F and solver; hierarchical_target_error.h)
  std::string hierarchical_transport = "form-factors";
  // --hierarchical --target-error: "adaptive" (the default): quads cut in bands where their shape or the direction of
  // the radiosity's variation inside them asks for it (hierarchy/split_kind.h), or "regular" 4-way splits
  std::string hierarchical_split = "adaptive";
  double hierarchical_cluster_ratio = 0.25;  // a cluster receives only where its radius <= ratio x the distance
  // --progressive DIR: ParaView series of the iterates (iterative solvers) or of the estimate after 1, 2, 4, ...
  // batches of walks (random-walk)
  std::string progressive;
};

struct CompareCommand {
  SceneOptions scene;
  FormFactorCliOptions ff;
  // Methods, runs, kernel and budget (walk.walks_per_patch), typed by the parser and checked once the scene is
  // loaded (check_compare_options); the seed is scene.seed.
  CompareOptions compare;
};

struct PathtraceCommand {
  SceneOptions scene;
  long spp = 64;
  std::string integrator = "mis";
  std::string image;
  int width = 256, height = 256;
  std::vector<double> camera;  // px py pz tx ty tz ux uy uz fov_deg (empty: the scene's default)
  std::string progressive;     // --progressive DIR: convergence series of the patch averages
};

// radwalk measure: one measurement M = <R, B>_A (solve/measurement.h) by one method.
struct MeasureCommand {
  SceneOptions scene;
  FormFactorCliOptions ff;
  std::string response;            // --response SPEC (apps/measure_response.h)
  std::string method = "adjoint-direct";  // direct | adjoint-direct | a walk method | importance-gather | importance-shoot
  WalkOptions walk;                // kernel and survival of the walk methods
  long walks = 100000;             // walks or particles in all (per channel for the importance walks)
  int importance_sweeps = -1;      // importance walks: -1 the exact importance (direct solve), K >= 0 K Jacobi sweeps
  double defensive = -1;           // importance walks: the defensive fraction alpha (importance_walk.h); -1: 0 with
                                   // the exact importance, 0.1 with an approximate one
  bool theory = false;             // also the exact per-walk variance (matrix kernel, N <= 2000)
  int discretisation_directions = 16;  // M_disc's directions per point (solve/fluctuation_source.h); 0: not estimated
  // --response camera: the view (as pathtrace's --camera; empty: the scene's default) and the image size
  std::vector<double> camera;
  int width = 256, height = 256;
};

// radwalk exchange: grey diffuse radiative heat exchange by the net-radiation method (solve/net_radiation.h).
struct ExchangeCommand {
  SceneOptions scene;
  FormFactorCliOptions ff;
  std::string solver = "auto";       // auto | direct | jacobi | gauss-seidel | southwell | gmres | random-walk
  WalkOptions walk;                  // --solver random-walk: the walks on the matrix kernel
  double tol = 1e-12;
  long max_iterations = 0;           // 0: the solver's default
  double ambient_temperature = 0;    // --ambient-temperature T (K): what escaping rays reach (emissivity 1)
  bool ambient_given = false;
  std::string group_by = "object";   // --group-by object|group|material
  std::string groups_csv;            // --groups FILE.csv: Q per group
  std::string group_factors;         // --group-factors FILE.csv: F between groups (from, to, F)
  std::string contact_faces = "include";  // --contact-faces include|exclude: patches touching other surfaces
  std::string sensitivities;         // --sensitivities all|G1,G2: response groups of dQ/deps, dQ/dT (adjoint)
  std::string sensitivities_csv;     // --sensitivities-csv FILE.csv: group_from,group_to,dQ_deps_W,dQ_dT_W_per_K
  int discretisation_directions = 16;  // --discretisation-directions L: J_disc (solve/exchange_discretisation.h); 0 off
};

int run_check(const SceneOptions& options);
int run_exchange(const ExchangeCommand& command);
int run_measure(const MeasureCommand& command);
int run_patch(const PatchCommand& command);
int run_formfactors(const FormFactorsCommand& command);
int run_solve(const SolveCommand& command);
int run_compare(const CompareCommand& command);
int run_pathtrace(const PathtraceCommand& command);

}  // namespace radwalk::app
