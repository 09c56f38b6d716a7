#pragma once
// The run metadata a .vtp carries as field data (io/vtp_metadata.h), from what the command already knows:
//   run_id (below), radwalk_version, git_commit (git describe of the source tree at build time, "unknown" outside a checkout),
//   command, command_line, scene, seed, max_edge, patches, length_unit, B_unit, B_srgb (the display mapping),
//   the form-factor ray count (rays: total traced, when F was estimated) or form_factors_file, and a
//   seconds_<stage> entry per stage timed so far in the RunSummary (spaces become underscores).
// solution_metadata adds what a Solution says: method, status, iterations and residual (deterministic solvers),
// walks and steps (random walks), solve_seconds, and for Monte Carlo results the standard-error summary
//   B_se_max           max over patches and channels of B_se
//   B_se_relative_rms  sqrt(sum_i A_i sum_c B_se_ic^2 / sum_i A_i sum_c B_ic^2) (area-weighted RMS of B_se
//                      relative to that of B)
#include "apps/options.h"
#include "apps/scene_camera.h"
#include "core/digest.h"
#include "core/solution.h"
#include "io/run_summary.h"
#include "io/vtp_metadata.h"
#include "patch/patch_set.h"
#include "solve/adaptive_refinement.h"
#include "solve/target_error.h"

namespace radwalk::app {

// The run id: 16 hexadecimal digits, the 64-bit FNV-1a digest (core/digest.h) of radwalk's version and git
// describe, the command and its canonical option values (options.run_options: every option as given or its
// default, except --threads, --quiet and the names of output files, of which only the presence counts) and the
// bytes of every input file in the order they were read (input_bytes: the scene, its MTL libraries, the
// --form-factors file). Deterministic: two runs with the same id compute the same outputs (up to the fields that
// record how a run went rather than what it computed: docs/reliability.md, "Run id"), and a change of any input
// byte or option value changes it. Every output carries it (the JSON key run_id, the .vtp field data run_id, a
// CSV column run_id, a comment in .mtx, .obj, .mtl and ParaView state files, an EXR header attribute, a PNG tEXt
// chunk), so that files of two different runs left side by side are told apart.
std::string run_id(const SceneOptions& options, const Digest& input_bytes);

// The run id load_validated_mesh recorded in the summary (json()["run_id"]), "" before.
std::string run_id_of(RunSummary& summary);

VtpMetadata run_metadata(const SceneOptions& options, RunSummary& summary);

VtpMetadata solution_metadata(const Solution& solution, const PatchSet& patches);

// The JSON "camera" object of `pathtrace --image` and `measure --response camera` (docs/json-schema.md): the same
// keys in both, position, look_at (camera_focal_point), direction (unit), up (3 numbers each, mesh units),
// vertical_fov_deg, width and height (pixels of the image or the response's film) and source (SceneCamera).
nlohmann::json camera_json(const SceneCamera& camera, const PatchSet& patches, int width, int height);

// One step of adaptive refinement as the JSON's refine.steps[k] (docs/json-schema.md), for `solve --refine` and
// radwalk.solve_adaptive alike: step, patches, marked, split, max_jump, method, iterations and the seconds of its
// form factors, solve, refinement and in all.
nlohmann::json refine_step_json(const RefineStep& step);

// One step of --target-error (solve/target_error.h) as the JSON's target_error.steps holds it.
nlohmann::json target_error_step_json(const TargetErrorStep& step);
// The counted groups of a target-error run (solve/group_mean_error.h): name, area, mean, the signed relative
// discretisation estimate and the relative discretisation, statistical and total errors of each group's mean.
nlohmann::json group_mean_errors_json(const std::vector<GroupMeanError>& groups);

}  // namespace radwalk::app
