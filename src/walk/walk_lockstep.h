#pragma once
// run_lockstep: walks advanced in lockstep, so that a kernel receives its destination samples in batches (the ray
// kernel traces each batch as one Embree packet of up to 16 rays).
//
// A walk (gather_estimators.h, shoot_estimators.h) is a state machine: done(); while not done, from() (the patch
// whose destination sample it waits for) and rng() (its own stream); step(walk, w, j) hands walk w the sample j.
// run_lockstep runs walks w = 0 .. count-1: make(w) returns walk w started (up to its first request or its end),
// finish(w, walk) receives it once done. Up to `lanes` walks (1..kMaxLanes) are in flight; each round asks
// kernel.sample for one destination of every walk in flight, steps them, and refills the lanes of finished walks
// with the next ones in order of w. Walks finish in any order, but every walk draws only from its own stream, in
// its own order, so each walk's outcome is the same for any `lanes` and any batch (up to a visibility whose answer
// for one ray depends on the other rays of its packet: Embree's does not, except perhaps for ties at equal t).
// lanes = 1 drives each walk alone through the single-sample kernel.sample(k, rng, counters).
// A walk may also give the uniforms of its next ray (uniforms(): 4 floats or nullptr; the Sobol sampler's first
// rays, stratified_emission.h): they go into its request (SampleRequest::u) instead of draws from its stream.
// A walk may also ask for the memory its step to j will read (prefetch(j), a hint with no effect on any value):
// run_lockstep calls it for every lane of a batch before stepping any, so that the cache misses of the lanes on
// their destinations' records (at large N, most accesses) overlap instead of coming one after the other.
#include <algorithm>
#include <array>
#include <cstddef>
#include <span>
#include <type_traits>

#include "core/cancellation.h"
#include "walk/transition_kernel.h"

namespace radwalk {

// The uniforms a walk gives for its next ray (SampleRequest::u), or nullptr: walks without uniforms() draw from
// their stream.
template <class Walk>
const float* walk_uniforms(const Walk& walk) {
  if constexpr (requires { walk.uniforms(); })
    return walk.uniforms();
  else
    return nullptr;
}

// walk.prefetch(j) where the walk has one.
template <class Walk>
void prefetch_step(const Walk& walk, PatchIndex j) {
  if constexpr (requires { walk.prefetch(j); }) walk.prefetch(j);
}

// One destination sample for one walk: through the batch call when the walk gives its uniforms.
template <TransitionKernel K, class Walk>
PatchIndex sample_one(const K& kernel, Walk& walk, WalkCounters& counters) {
  if (const float* u = walk_uniforms(walk)) {
    const SampleRequest request{walk.from(), &walk.rng(), u};
    PatchIndex j = kEscaped;
    kernel.sample(std::span<const SampleRequest>(&request, 1), std::span<PatchIndex>(&j, 1), counters);
    return j;
  }
  return kernel.sample(walk.from(), walk.rng(), counters);
}

// Both poll the cancellation request (core/cancellation.h) every this many walks started: a chunk of a shooting
// run can hold millions of particles.
constexpr std::size_t kWalksPerCancellationPoll = 1024;

// The walks one at a time (run_lockstep with lanes = 1; a function of its own, small enough for the compiler to
// inline the kernel and the walk into it).
template <TransitionKernel K, class Make, class Step, class Finish>
void run_singly(const K& kernel, std::size_t count, Make&& make, Step&& step, Finish&& finish,
                WalkCounters& counters) {
  for (std::size_t w = 0; w < count; ++w) {
    if (w % kWalksPerCancellationPoll == 0) throw_if_cancelled();
    auto walk = make(w);
    while (!walk.done()) step(walk, w, sample_one(kernel, walk, counters));
    finish(w, walk);
  }
}

template <TransitionKernel K, class Make, class Step, class Finish>
void run_lockstep(const K& kernel, std::size_t count, std::size_t lanes, Make&& make, Step&& step, Finish&& finish,
                  WalkCounters& counters) {
  using Walk = std::invoke_result_t<Make&, std::size_t>;
  lanes = std::clamp<std::size_t>(lanes, 1, kMaxLanes);
  if (lanes == 1) return run_singly(kernel, count, make, step, finish, counters);
  std::array<Walk, kMaxLanes> walk;
  std::array<std::size_t, kMaxLanes> index{};  // the walk number in each lane
  std::size_t next = 0, active = 0;
  // Starts walks in order in `lane` until one is still running (true) or none is left (false).
  auto fill = [&](std::size_t lane) {
    while (next < count) {
      if (next % kWalksPerCancellationPoll == 0) throw_if_cancelled();
      index[lane] = next;
      walk[lane] = make(next++);
      if (!walk[lane].done()) return true;
      finish(index[lane], walk[lane]);
    }
    return false;
  };
  while (active < lanes && fill(active)) ++active;
  std::array<SampleRequest, kMaxLanes> request;
  std::array<PatchIndex, kMaxLanes> destination{};
  while (active > 0) {
    // One batch: a destination for every walk in flight.
    for (std::size_t r = 0; r < active; ++r) request[r] = {walk[r].from(), &walk[r].rng(), walk_uniforms(walk[r])};
    kernel.sample(std::span<const SampleRequest>(request.data(), active),
                  std::span<PatchIndex>(destination.data(), active), counters);
    for (std::size_t r = 0; r < active; ++r) prefetch_step(walk[r], destination[r]);
    // Step each. A finished walk's lane takes the next walk or, when none is left, the last lane's walk (not yet
    // stepped this round, so this lane is stepped again).
    for (std::size_t r = 0; r < active;) {
      step(walk[r], index[r], destination[r]);
      if (!walk[r].done()) {
        ++r;
        continue;
      }
      finish(index[r], walk[r]);
      if (fill(r)) {
        ++r;
        continue;
      }
      --active;
      if (r < active) {
        walk[r] = walk[active];
        index[r] = index[active];
        destination[r] = destination[active];
      }
    }
  }
}

}  // namespace radwalk
