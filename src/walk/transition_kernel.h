#pragma once
// The transition-kernel interface every random-walk estimator runs on, and the per-patch data a kernel gives
// about its chain. A kernel knows nothing of the estimators that run on it (gather_estimators.h,
// shoot_estimators.h build their own weight tables from this data).
//
// Per channel c the system is B_c = E_c + H_c B_c with H_c = diag(rho_c) F. A kernel is a Markov chain on
// patches built from two pieces:
//   - a survival probability p_k (Russian roulette, one scalar for all channels), and
//   - a destination sampler: from patch k, patch j with probability F_kj / n_k, else a stop (kEscaped: the walk
//     left an open scene; kBackHit: a ray hit the back of a patch). n_k >= 1 is the row scale (alias_table.h;
//     1 for the ray kernel). A destination sample from k is a stop with probability 1 - s_k / n_k, s_k the row
//     sum of F.
// Gathering walks use P_kj = p_k F_kj / n_k (roulette at k, then move) and weight factor
//   w_k = H_kj / P_kj = rho_k n_k / p_k   (per channel; = rho_k / p_k for the analog walk, 1 if p_k = rho_k),
// shooting particles move first and roulette at the patch they reach (shoot_estimators.h).
// A kernel K provides (all const, thread-safe, O(1) except the ray tracing):
//   size(), tables() (KernelTables below: E_k, rho_k, p_k, n_k and, where the kernel knows them, the row sums
//     s_k),
//   static constexpr bool kHESampled: (H E)_k is estimated from one extra destination sample j of k (see HE),
//     rather than known exactly,
//   static constexpr std::size_t kLanes (1..kMaxLanes): how many walks the drivers advance in lockstep
//     (walk_lockstep.h), i.e. the batch size the kernel prefers,
//   sample(k, rng, counters)   -> PatchIndex: j >= 0 with probability F_kj / n_k, else kEscaped / kBackHit,
//   sample(requests, out, counters): out[r] = sample(requests[r].k, *requests[r].rng, counters) for every r, as
//     one batch (the ray kernel traces them as packets). Each request draws only from its own stream, exactly as
//     the single call does, so a walk's outcome does not depend on the other walks of its batch,
//   HE(k, j)                   -> Rgb: with kHESampled, rho_k E_j (0 for a stop j < 0) for a destination sample
//     j of k, whose expectation is (H E)_k; without, (H E)_k = rho_k sum_j F_kj E_j exactly (j is ignored: no
//     sample is drawn, the estimators pass kNoSample).
// The two kernels differ for an estimator in two facts only, both data here: whether the row sums s_k, and so the
// stop probability 1 - s_k / n_k of a destination sample, are known (matrix kernel: the row deficit; ray kernel:
// unknown without F), and whether (H E)_k is exact or sampled (kHESampled).
#include <concepts>
#include <cstddef>
#include <span>
#include <vector>

#include "core/rng.h"
#include "core/types.h"

namespace radwalk {

// Walk stop codes: what sample() returns for a destination that is not a patch. Both end the walk.
inline constexpr PatchIndex kEscaped = -1;  // the walk left the scene (row deficit, or a ray that hit nothing)
inline constexpr PatchIndex kBackHit = -2;  // a ray hit the back of a patch (ray kernel)

// A uniform number in [0, 1) from one 32-bit draw, for Russian roulette (u < p_k): the survival probability is
// then resolved to 2^-32, far below any Monte Carlo error, at half the cost of Rng::uniform().
inline double roulette_uniform(Rng& rng) { return static_cast<double>(rng.next_u32()) * 0x1.0p-32; }

// Tallies a walk or a particle keeps while it runs (summed per chunk, in chunk order).
struct WalkCounters {
  long steps = 0;      // destination samples (alias draws or traced rays, including next-event rays)
  long escapes = 0;    // samples that left the scene
  long back_hits = 0;  // rays that hit the back of a patch
  WalkCounters& operator+=(const WalkCounters& o) {
    steps += o.steps;
    escapes += o.escapes;
    back_hits += o.back_hits;
    return *this;
  }
};

// What a kernel tells the estimators about its chain, per patch k (Rgb rows are per channel).
struct KernelTables {
  std::vector<Rgb> E;      // emitted radiosity E_k
  std::vector<Rgb> rho;    // reflectance rho_k
  std::vector<double> p;   // survival probability p_k
  std::vector<double> n;   // row scale n_k
  // Row sum s_k of F where the kernel knows it (matrix kernel), so that a destination sample from k is known to
  // be a stop with probability 1 - s_k / n_k; empty where it does not (ray kernel: the escape probability of a
  // ray is not known without F).
  std::vector<double> s;
  bool row_sums_known() const { return !s.empty(); }
};

// E and rho as rows per patch, with p, n and s (empty: unknown) as given.
KernelTables make_kernel_tables(const PatchRgb& rho, const PatchRgb& E, std::vector<double> p, std::vector<double> n,
                                std::vector<double> s);

// One destination-sample request of a batch: a sample from patch k, drawn from the walk's own stream; or, when u
// is set, a ray made from the four given uniforms u[0..3] in [0, 1) (point u[0], u[1]; direction u[2], u[3]) with
// nothing drawn from the stream (the ray kernel; the Sobol sampler's first rays, quasi_random_shoot.h). A kernel
// that makes no rays (the matrix kernel) ignores u and draws from the stream.
struct SampleRequest {
  std::size_t k = 0;
  Rng* rng = nullptr;
  const float* u = nullptr;
};

// HE(k, j)'s j for a kernel without kHESampled: no destination sample was drawn.
inline constexpr PatchIndex kNoSample = -3;

// The largest batch a lockstep driver hands a kernel at once (one Embree packet of 16 rays).
inline constexpr std::size_t kMaxLanes = 16;

template <class K>
concept TransitionKernel = requires(const K& kernel, std::size_t k, PatchIndex j, Rng& rng, WalkCounters& counters,
                                    std::span<const SampleRequest> requests, std::span<PatchIndex> out) {
  { kernel.size() } -> std::convertible_to<std::size_t>;
  { kernel.tables() } -> std::convertible_to<const KernelTables&>;
  { kernel.sample(k, rng, counters) } -> std::convertible_to<PatchIndex>;
  kernel.sample(requests, out, counters);
  { kernel.HE(k, j) } -> std::convertible_to<Rgb>;
  { K::kHESampled } -> std::convertible_to<bool>;
  { K::kLanes } -> std::convertible_to<std::size_t>;
};

}  // namespace radwalk
