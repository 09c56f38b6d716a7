#pragma once
// The statistical error of a solution from form factors traced by rays: their noise propagated to B
// (formfactor/form_factor_noise.h, formfactor/sampling_factor.h, solve/error_propagation.h), combined with the
// solver's own Monte Carlo error where it has one (matrix-kernel walks: independent of F's noise given F, so the
// variances add: Var(B) = E[Var(B | F)] + Var(E[B | F])).
//
// Sets solution.B_se to the total statistical standard error (1 standard deviation, all sources); records in the
// JSON's "error_estimate" the parts (relative_error below), the sampling factors with their rows and replicates,
// the probes and the seconds; and returns the summary line to print. With F read from a file (no ray counts) F's
// noise is unknown: B_se keeps the solver's own part only, and the line and the JSON say that F's noise is not
// included.
#include <string>

#include "core/solution.h"
#include "formfactor/form_factors.h"
#include "io/run_summary.h"
#include "patch/patch_set.h"
#include "solve/form_factor_error.h"
#include "solve/group_mean_error.h"
#include "solve/problem.h"
#include "solve/target_error.h"

namespace radwalk::app {

// `ff` describes how problem.F was obtained (its F may have been moved into the problem). Collective over MPI
// when problem.F is row-distributed (each process works on its rows; the same result as one process). noise, if
// given, receives B_se's model for the groups' means (solve/group_mean_error.h: F's row noise when measured, the
// solver's own standard error when it has one).
std::string add_statistical_error(const PatchSet& patches, const FormFactors& ff, const RadiosityProblem& problem,
                                  Solution& solution, RunSummary& summary, GroupNoiseModel* noise = nullptr);

// The JSON record and summary line of add_statistical_error for a solution whose B_se is already set (by
// add_form_factor_error, solve/form_factor_error.h, alone or through solve/target_error_stage.h): own_se the
// solver's own standard error before (empty when it has none), error F's noise in B (nullptr when F records no
// tracing), seconds the time of that estimate.
std::string report_statistical_error(const PatchSet& patches, const FormFactors& ff, const Solution& solution,
                                     const PatchRgb& own_se, const FormFactorError* error, double seconds,
                                     RunSummary& summary);

// relative_error (the relative error e of the benchmarks for a per-patch error): solve/target_error.h.

// A relative error as the summary lines print it: "0.63 %" (two significant digits).
std::string percent(double x);

}  // namespace radwalk::app
