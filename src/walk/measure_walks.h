#pragma once
// Monte Carlo estimators of a measurement M_c = <R, B_c>_A = sum_i A_i R_i B_ic (solve/measurement.h), per
// channel, by every random-walk method of walk_method.h and by importance-driven walks (importance_walk.h).
//
// Adjoint (gathering methods; from the sensor): a walk starts at patch i with probability
//   pi_i = A_i R_i / sum_j A_j R_j
// and runs the method's gathering walk from i (gather_estimators.h: absorption, collision, expected value), whose
// score X_i has E[X_i] = B_i; it scores Z = (sum_j A_j R_j) X_i, so E[Z] = sum_i A_i R_i B_i = M. Every walk ends
// on an emitter's score, none is wasted on patches the sensor does not see. Exact per-walk variance (matrix
// kernel): E[Z^2] = (sum A R)^2 sum_i pi_i s_i with s_i = var_i + B_i^2 from walk_variance.h.
// Forward (shooting methods; from the sources): the method's particles (shoot_estimators.h) score reflected
// power `power` at patch j; a particle scores Z = M_emitted + sum over its scores of R_j power, M_emitted = sum_j A_j R_j E_j
// the emitted part (known exactly), so E[Z] = M_emitted + sum_j R_j A_j (B_j - E_j) = M. Exact per-particle variance
// (matrix kernel, rows T = A^-1 F^T A with row scales n_k, survival p): for a unit weight leaving k, the mean
// u_k and second moment v_k of its later score S = sum R_j power solve
//   u = T D (R + u),                    D = diag(rho_c),
//   v = N T diag(rho^2) a + N T diag(rho^2 / p) v,   N = diag(n),   with a_j per estimator:
//     collision  R_j^2 + 2 R_j u_j,   absorption  R_j^2 / (1 - p_j),   survival  (R_j^2 + 2 R_j u_j) / p_j,
//   (a particle arriving at j with weight w scores w rho_j R_j (collision), w rho_j R_j / (1 - p_j) if absorbed
//   (absorption), or leaves with w rho_j / p_j and scores that (survival)), and
//   E[(Z - M_emitted)^2] = sum_i pi_i W0_i^2 v_i,  var = that - (M - M_emitted)^2.
// Importance-driven (matrix kernel): one importance chain per channel (importance_walk.h) from the sensor with
// importance g ~ B_c, or from the sources with g ~ Y_c (the adjoint solution); zero variance with the exact one.
// Streams: walk w of the adjoint and forward estimators is (seed, measure_walk, 0, w) (the adjoint walk draws its
// start first, then walks on the same stream); importance walk w of channel c is (seed, importance_walk, c, w).
// Walks run in fixed chunks merged in order: the same seed gives the same M whatever the thread count.
#include <string>

#include "core/types.h"
#include "patch/patch_set.h"
#include "solve/measurement.h"
#include "solve/problem.h"
#include "visibility/visibility.h"
#include "walk/survival.h"
#include "walk/transition_kernel.h"
#include "walk/walk_method.h"
#include "walk/walk_options.h"

namespace radwalk {

struct MeasureEstimate {
  std::string method;      // method name ("gather-collision", "importance-gather", ...)
  Rgb M = Rgb::Zero();     // estimate per channel
  Rgb se = Rgb::Zero();    // its standard error
  Rgb var = Rgb::Zero();   // per-walk sample variance
  Rgb var_theory = Rgb::Constant(std::numeric_limits<double>::quiet_NaN());  // exact per-walk variance, or NaN
  long walks = 0;          // walks (per channel for the importance walks)
  WalkCounters counters;
  double seconds = 0;
};

// The adjoint (gathering method) or forward (shooting method) estimator of `options.method` on options.kernel,
// with `walks` walks or particles in all (options.walks_per_patch and options.particles are not read). The
// ray kernel needs `patches` and `visibility`; the matrix kernel problem.F. With theory (matrix kernel, N <=
// kMaxTheoryPatches) var_theory is filled. Throws InputError on a bad response or options.
MeasureEstimate measure_random_walk(const RadiosityProblem& problem, const PatchSet* patches,
                                    const Visibility* visibility, const WalkOptions& options,
                                    const Response& response, long walks, bool theory);

enum class ImportanceDirection { from_sensor, from_sources };

// Importance-driven walks, `walks` per channel, over the matrix kernel's F: from the sensor with importance
// `importance` ~ B (N x 3), or from the sources with `importance` ~ Y (the adjoint solution, N x 3); defensive
// fraction alpha (importance_walk.h; 0 with an exact importance gives zero variance).
MeasureEstimate measure_importance(const RadiosityProblem& problem, const Response& response,
                                   ImportanceDirection direction, const PatchRgb& importance, double alpha,
                                   long walks, std::uint64_t seed, bool theory);

}  // namespace radwalk
