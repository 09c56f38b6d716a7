#pragma once
// One measurement M = <R, B>_A by any method of `radwalk measure --method` (and radwalk.measure(method=...)):
//   direct             LU solve of B (solve/direct_solver.h), then M = <R, B>_A; exact, no standard error
//   adjoint-direct     LU solve of the adjoint system Y, then M = <Y, E>_A (solve/measurement.h)
//   importance-gather  importance walks from the sensor with g ~ B, importance-shoot from the sources with
//                      g ~ Y (walk/importance_walk.h): the exact g (an LU) when importance_sweeps < 0, else
//                      importance_sweeps Jacobi sweeps (partial_radiosity / partial_importance); defensive
//                      fraction alpha = defensive, or when < 0: 0 with the exact g, 0.1 with the swept one
//   a walk method      the adjoint (gathering) or forward (shooting) estimator of walk_method.h
//                      (walk/measure_walks.h) on options.walk.kernel
// `walks` walks or particles in all (per channel for the importance walks), seed options.walk.seed.
#include <string>
#include <vector>

#include "patch/patch_set.h"
#include "solve/measurement.h"
#include "solve/problem.h"
#include "visibility/visibility.h"
#include "walk/measure_walks.h"
#include "walk/walk_options.h"

namespace radwalk {

struct MeasureOptions {
  std::string method = "direct";
  long walks = 100000;
  WalkOptions walk;            // kernel, survival, seed, ... (method, walks_per_patch and particles set from above)
  int importance_sweeps = -1;  // < 0: the exact importance
  double defensive = -1;       // < 0: the default above
  bool theory = false;         // also the exact per-walk variance (matrix kernel)
};

// The methods' names: direct, adjoint-direct, importance-gather, importance-shoot, then walk_method_names().
std::vector<std::string> measure_method_names();

bool is_deterministic_measure(const std::string& method);  // direct, adjoint-direct
bool is_importance_measure(const std::string& method);     // importance-gather, importance-shoot

// The one check of MeasureOptions, before any form factor is traced: InputError for an unknown method (with the
// valid names and the nearest), bad walk options, or an LU (direct, adjoint-direct, the exact importance) of more
// than kDenseMaxPatches patches (a sparse LU of F fills in and takes minutes to hours).
void check_measure_options(const MeasureOptions& options, std::size_t patch_count);

// False only for a walk method on the ray kernel (no F is stored: problem.F may be empty).
bool measure_needs_form_factors(const MeasureOptions& options);

struct Measurement {
  MeasureEstimate estimate;          // M, se, var, var_theory (NaN where not computed), walks, counters, seconds
  bool deterministic = false;        // direct or adjoint-direct: se = var = 0, no walks
  std::string importance_source;     // importance walks: "direct" (exact g) or "jacobi"
  double defensive = 0;              // importance walks: the alpha used
};

// M by options.method; the caller has checked the options (check_measure_options: the one check, before any form
// factor is traced). The ray kernel needs patches and visibility; every other method problem.F. Throws
// NumericalError if an LU solve fails, or if M, its standard error or its per-walk sample variance does not fit a
// double (every method alike: never an infinite or NaN result).
Measurement measure_by_method(const RadiosityProblem& problem, const PatchSet* patches, const Visibility* visibility,
                              const Response& response, const MeasureOptions& options);

}  // namespace radwalk
