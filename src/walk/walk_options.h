#pragma once
// Options of the discrete random-walk solvers and the names of their methods.
//
// Methods ("walk-estimator"): gather-absorption, gather-collision, gather-expected-value (estimate chosen patches,
// `walks` walks per patch) and shoot-collision, shoot-absorption, shoot-survival (estimate all patches, `walks`
// particles in total). Kernels: "matrix" (stored F, alias tables) or "ray" (trace each step, needs a PatchSet and
// a Visibility). Survival p_k: "analog" (mean rho_k over channels), "max", "constant" (survival_constant).
// Random streams (core/rng.h): gathering walk w from patch i is (seed, gather_walk, i, w); shooting particle w is
// (seed, shoot_particle, 0, w). Results are bit-identical for any thread count.
#include <cstdint>
#include <string>
#include <vector>

#include "walk/gather_estimators.h"
#include "walk/shoot_estimators.h"

namespace radwalk {

struct WalkOptions {
  std::string walk = "gather";           // "gather" | "shoot"
  std::string estimator = "absorption";  // gather: absorption | collision | expected-value;
                                         // shoot: collision | absorption | survival
  std::string kernel = "matrix";         // "matrix" | "ray"
  long walks = 1000;                     // per patch (gather) or particles in total (shoot), >= 2
  std::uint64_t seed = 1;
  std::vector<int> patches;              // gather: patches to estimate (empty = all); shoot: ignored
  std::string survival = "analog";       // "analog" | "max" | "constant"
  double survival_constant = 0.5;        // p for survival = "constant", in (0, 1)
  bool theory = false;                   // also fill Solution::var_theory (matrix kernel, N <= kMaxTheoryPatches)
};

// The six method names, in a fixed order.
const std::vector<std::string>& walk_methods();
// "gather-absorption" etc. for the options' walk and estimator.
std::string method_name(const WalkOptions& options);
// Sets walk and estimator from a method name; InputError listing the valid names otherwise.
void set_method(WalkOptions& options, const std::string& method);

// Throws InputError with a clear message on an unknown or invalid combination (e.g. shoot + expected-value),
// walks < 2, or a patch index outside [0, patch_count).
void check_walk_options(const WalkOptions& options, std::size_t patch_count);

GatherEstimator gather_estimator(const WalkOptions& options);
ShootEstimator shoot_estimator(const WalkOptions& options);

}  // namespace radwalk
