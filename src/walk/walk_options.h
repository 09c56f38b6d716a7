#pragma once
// Options of the discrete random-walk solvers, typed, and their one check.
//
// method     the direction and estimator (walk_method.h: the list of methods, their names and parser);
// kernel     matrix (stored F, alias tables) or ray (trace each step; needs a PatchSet and a Visibility);
// counts     gathering methods estimate the chosen patches with walks_per_patch walks each; shooting methods
//            estimate all patches from `particles` particles in total (each count is read only by its direction);
// survival   the roulette rule (survival.h).
// Random streams (core/rng.h): gathering walk w from patch i is (seed, gather_walk, i, w); shooting particle w is
// (seed, shoot_particle, 0, w). Results are bit-identical for any thread count.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "walk/named_choice.h"
#include "walk/survival.h"
#include "walk/walk_method.h"

namespace radwalk {

enum class WalkKernel { matrix, ray };

inline constexpr std::array<NamedChoice<WalkKernel>, 2> kWalkKernels = {{
    {WalkKernel::matrix, "matrix", "stored F, an alias table per row"},
    {WalkKernel::ray, "ray", "Embree traces every step, no F stored"},
}};
static_assert(in_enum_order(kWalkKernels));

constexpr std::string_view kernel_name(WalkKernel kernel) { return choice_name(kWalkKernels, kernel); }

// "matrix" | "ray"; InputError naming the valid kernels otherwise.
WalkKernel parse_walk_kernel(std::string_view name);

// How a shooting run draws its particles (random_walk_solver.h):
//   random  i.i.d. particles: births from the alias table, every ray from the particle's stream;
//   sobol   R = replicates independent randomisations, each with particles / R particles allocated to the
//           sources systematically and first rays from randomised Sobol points (stratified_emission.h); with
//           direct_light the first bounce is computed apart (direct_light.h) and the particles carry the
//           indirect light only. Standard errors come from the spread of the replicates.
//   jacobi  stochastic Jacobi (shoot-collision only; stochastic_jacobi.h): bounce by bounce, each bounce's power
//           re-shot by stratified emission with rays in proportion to it; replicates as sobol; with direct_light
//           the first shot is the direct light.
enum class WalkSampler { random, sobol, jacobi };

inline constexpr std::array<NamedChoice<WalkSampler>, 3> kWalkSamplers = {{
    {WalkSampler::random, "random", "independent particles, pseudo-random"},
    {WalkSampler::sobol, "sobol", "stratified emission, randomised Sobol first rays, replicates for the error bars"},
    {WalkSampler::jacobi, "jacobi",
     "stochastic Jacobi: each bounce re-shot by stratified emission, rays in proportion to its power"},
}};
static_assert(in_enum_order(kWalkSamplers));

constexpr std::string_view sampler_name(WalkSampler sampler) { return choice_name(kWalkSamplers, sampler); }

// "random" | "sobol"; InputError naming the valid samplers otherwise.
WalkSampler parse_walk_sampler(std::string_view name);

struct WalkOptions {
  WalkMethod method = WalkMethod::gather_collision;
  WalkKernel kernel = WalkKernel::matrix;
  long walks_per_patch = 1000;  // gathering: walks from each estimated patch, >= 2
  long particles = 1000;        // shooting: particles in total, >= 2
  std::uint64_t seed = 1;
  std::vector<int> patches;     // gathering: patches to estimate (empty = all); shooting: ignored
  Survival survival;
  bool theory = false;          // also fill Solution::var_theory (matrix kernel, N <= kMaxTheoryPatches)
  bool progress = false;        // a progress line on stderr over the walks (core/progress.h)
  bool control_variate = false; // gathering, F stored: walk B - c from the shifted source (control_variate.h)
  // Shooting only (refused for gathering unless at their defaults):
  WalkSampler sampler = WalkSampler::random;
  int replicates = 4;           // sobol: independent randomisations, >= 2 (the error bars' degrees of freedom + 1)
  bool direct_light = false;    // sobol: the first bounce from the emitters computed apart (direct_light.h)
  long shadow_rays = 0;         // direct_light, ray kernel: shadow samples per receiving patch over all replicates
                                // (0: particles / (2 N), at least 16 per replicate)
  bool direct_sampled = false;  // direct_light, ray kernel: point-to-point shadow rays (estimate_direct_light)
                                // instead of the point-to-polygon form factors x visibility (the default)
};

// The one check of WalkOptions: InputError with a one-line message on a count below 2 (of the method's
// direction), a survival choice check_survival refuses, or a patch index outside [0, patch_count).
void check_walk_options(const WalkOptions& options, std::size_t patch_count);

// Walks the method runs: walks_per_patch x (patches estimated) for gathering, particles for shooting.
long total_walks(const WalkOptions& options, std::size_t patch_count);

// The most walks (or particles) one run counts: 2^48, far beyond any run's time, and far below where the counts
// (walks x patches, x runs in compare) would overflow.
inline constexpr long kMaxWalkCount = long{1} << 48;

}  // namespace radwalk
