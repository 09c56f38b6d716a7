#pragma once
// `radwalk solve SCENE --target-error E`: the steps of solve/target_error.h on the command's traced form-factor
// route (its --rays as the first step's, Sobol rays and emitter columns as the command says, the automatic
// solver), each step's errors estimated as a plain solve's (apps/statistical_error.h, apps/discretisation_error.h).
// The first step's form factors report as a plain solve's do (obtain_form_factors: notes, warnings, JSON); every
// step prints a progress line. Records "target_error" in the JSON (target, budgets, reached, stop_reason,
// seconds, steps) and leaves the last step's "error_estimate".
#include <string>

#include "apps/options.h"
#include "io/run_summary.h"
#include "patch/patch_set.h"
#include "solve/target_error.h"

namespace radwalk::app {

struct TargetErrorRun {
  TargetErrorResult result;
  std::string error_line;  // the last step's summary line(s) of its estimated error
};

TargetErrorRun run_target_error(const SolveCommand& command, PatchSet patches, RunSummary& summary);

// The groups whose means a target-error run holds (TargetErrorOptions::each): --target-each, its default
// (material) when not given, "" for none. can_hold: the route can (false: the default is none, and an explicit
// group is left for the route to refuse).
std::string target_groups(const SolveCommand& command, bool can_hold);

// The part of a step's progress line about the groups ("; 17 of 18 materials within 1.6 % (largest: sofa 2.3 %)":
// within kGroupTargetFraction x the run's target), "" without groups.
std::string group_progress(const TargetErrorStep& step, const std::string& each, double target);

// One step's work of that route on given patches with given rays per patch: F traced (the first step's through
// obtain_form_factors when first_obtains, else trace_form_factors, which reports nothing), then the step shared with
// Python (solve/target_error_stage.h: the automatic solver, B_se and B_disc), reported as a plain solve's (their
// JSON "error_estimate" and the line in error_line, overwritten each step; the materials' means only when the run
// does not hold them, target_groups(command, true) != "material": else report_held_materials). The hierarchical route's form-factor
// transport uses it with first_obtains false and attribute_shooters true: each step also gives the patches' shooter
// shares (solve/shooter_attribution.h) for the refinement (solve/refinement_marks.h). The uniform route does not
// ask for them: measured on the Cornell box they cost about a third more CPU per step and changed nothing
// (docs/theory/discretisation_error.md, "Refinement by both shares").
TargetErrorWork form_factor_target_work(const SolveCommand& command, RunSummary& summary, std::string& error_line,
                                        bool first_obtains, bool attribute_shooters = false);

// With each == "material": the last step's groups (run.result.groups, the materials' means the run computed for its
// target) reported as a plain solve's materials (report_material_means, apps/discretisation_error.h: the JSON's
// error_estimate.materials and a line appended to run.error_line), so that each step computes them once.
void report_held_materials(const std::string& each, TargetErrorRun& run, RunSummary& summary);

}  // namespace radwalk::app
