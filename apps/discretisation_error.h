#pragma once
// The estimated discretisation error of a solution (solve/discretisation_error.h) and the total error it makes
// with the statistical one (apps/statistical_error.h), for the summary line, the JSON and the per-patch fields.
//
// Sets solution.B_disc (1 standard deviation equivalent per patch and channel); records in the JSON's
// "error_estimate" the part "discretisation" (relative error, points, directions, rays, the method) and "total"
// (relative error of B_err = sqrt(B_se^2 + B_disc^2)), and "materials", each material's mean with its own errors
// (solve/group_mean_error.h), when the problem holds every row of a solved F; returns the summary line
//   "estimated error e = 0.9 % (statistical 0.4 %, discretisation 0.8 %; ...)"
// and, with the materials, a second line naming the largest error of a material's mean.
#include <string>
#include <vector>

#include "core/solution.h"
#include "io/run_summary.h"
#include "patch/patch_set.h"
#include "solve/discretisation_error.h"
#include "solve/group_mean_error.h"
#include "solve/problem.h"

namespace radwalk::app {

// directions: L of solve/fluctuation_source.h (0: not estimated, returns ""). Collective over MPI when problem.F is
// row-distributed. noise: B_se's model (add_statistical_error's, apps/statistical_error.h), which makes the
// materials' statistical parts first-order (solve/group_mean_error.h; empty: their bound).
std::string add_discretisation_error(const PatchSet& patches, const RadiosityProblem& problem, Solution& solution,
                                     RunSummary& summary, int directions, std::uint64_t seed,
                                     const GroupNoiseModel& noise = {});

// The JSON record and summary lines of add_discretisation_error for a solution whose B_disc is already set from
// `error` (alone or through solve/target_error_stage.h); `problem` the one B solves. materials false: the
// materials' means are left to the caller (a run that computes them anyway, --target-error's groups:
// report_material_means below).
std::string report_discretisation_error(const PatchSet& patches, const RadiosityProblem& problem,
                                        const DiscretisationError& error, const Solution& solution,
                                        RunSummary& summary, const GroupNoiseModel& noise = {},
                                        bool materials = true);

// The materials' means (group_mean_errors of group_patches(patches, "material")) in the JSON's
// error_estimate.materials, and the summary line naming the largest error of a material's mean ("" when no
// material is counted).
std::string report_material_means(const std::vector<GroupMeanError>& means, RunSummary& summary);

}  // namespace radwalk::app
