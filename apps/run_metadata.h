#pragma once
// The run metadata a .vtp carries as field data (io/vtp_metadata.h), from what the command already knows:
//   radwalk_version, git_commit (git describe of the source tree at build time, "unknown" outside a checkout),
//   command, command_line, scene, seed, max_edge, patches, length_unit, B_unit, B_srgb (the display mapping),
//   the form-factor ray count (rays: total traced, when F was estimated) or form_factors_file, and a
//   seconds_<stage> entry per stage timed so far in the RunSummary (spaces become underscores).
// solution_metadata adds what a Solution says: method, status, iterations and residual (deterministic solvers),
// walks and steps (random walks), solve_seconds, and for Monte Carlo results the standard-error summary
//   B_se_max           max over patches and channels of B_se
//   B_se_relative_rms  sqrt(sum_i A_i sum_c B_se_ic^2 / sum_i A_i sum_c B_ic^2) (area-weighted RMS of B_se
//                      relative to that of B)
#include "apps/options.h"
#include "core/solution.h"
#include "io/run_summary.h"
#include "io/vtp_metadata.h"
#include "patch/patch_set.h"

namespace radwalk::app {

VtpMetadata run_metadata(const SceneOptions& options, RunSummary& summary);

VtpMetadata solution_metadata(const Solution& solution, const PatchSet& patches);

}  // namespace radwalk::app
