#pragma once
// `radwalk solve SCENE --hierarchical --target-error E`: the steps of hierarchy/hierarchical_target_error.h on the
// element trees of the scene's patches (--rays the first step's rays per leaf, --max-patches the budget of leaves,
// --max-seconds the time's, --discretisation-directions the estimates' directions; --hierarchical-levels,
// -min-area, -points and -replicates as for --hierarchical). Every step prints a progress line. Returns the run as
// the uniform route's (apps/target_error.h): the leaves as patches (each with its input face), the last step's
// solution with B_se and B_disc, no form factors. Records in the JSON "target_error" (target, budgets, reached,
// stop_reason, seconds, steps with leaves, rays per leaf, rays, the three errors and seconds), "hierarchy" and the
// last step's "error_estimate".
#include "apps/options.h"
#include "apps/target_error.h"
#include "io/run_summary.h"
#include "patch/patch_set.h"

namespace radwalk::app {

TargetErrorRun run_hierarchical_target_error(const SolveCommand& command, const PatchSet& roots, RunSummary& summary);

}  // namespace radwalk::app
