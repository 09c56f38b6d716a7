#pragma once
// Gathering (adjoint) random-walk estimators of B_i, one walk each, over any TransitionKernel.
//
// A walk starts at k_0 = i with weight W_0 = 1 (per channel). At state k_m it survives with probability p_k
// (roulette, roulette_uniform) and then moves to j with probability F_kj / n_k (kernel.sample); the survivor's weight
// is W_{m+1} = W_m w_k, w_k = rho_k n_k / p_k = H_kj / P_kj. It stops at k_tau by roulette or escape.
// All three are unbiased for B_i = E_i + sum_j H_ij B_j (per channel):
//   absorption     X = W_tau E_{k_tau} / q_{k_tau}, scored only at a kernel's scored stop (transition_kernel.h):
//                  E[X_i] = q_i E_i / q_i + sum_j P_ij w_i E[X_j].              (von Neumann-Ulam)
//   collision      X = sum_{m=0..tau} W_m E_{k_m}: E[X_i] = E_i + sum_j P_ij w_i E[X_j].   (Wasow)
//   expected value X = E_i + sum_{m=0..tau} W_m (H E)_{k_m}: scores at each state the expectation of the next
//                  step's emission (next-event estimation); with Y = X - E, E[Y_i] = (HE)_i + sum_j H_ij E[Y_j],
//                  so E[Y] = (I - H)^-1 H E = B - E. (H E)_k is kernel.HE(k, j), with j one extra destination
//                  sample drawn before the roulette where the kernel samples it (kHESampled).
//
// Each estimator is a small state machine (the walk of walk_lockstep.h), so that one code serves a walk run on
// its own (gather_walk) and walks advanced in lockstep, many destination samples per kernel call:
//   constructed from (kernel, i, rng): runs up to its first destination request or its end;
//   done()        true once the walk has stopped; score() is then X;
//   from(), rng() while not done: the patch whose destination sample it waits for, and its stream;
//   advance(j)    consumes that sample and runs up to the next request or the end.
// A walk draws from its own stream only, in the same order however it is driven: per state the roulette, then
// the destination sample (expected value with kHESampled: HE sample, roulette, destination sample).
#include "core/rng.h"
#include "walk/transition_kernel.h"

namespace radwalk {

enum class GatherEstimator { absorption, collision, expected_value };

template <TransitionKernel K>
class GatherAbsorption {
 public:
  GatherAbsorption() = default;
  GatherAbsorption(const K& kernel, std::size_t i, const Rng& rng) : t_(&kernel.tables()), k_(i), rng_(rng) {
    roulette();
  }
  bool done() const { return done_; }
  const Rgb& score() const { return X_; }
  std::size_t from() const { return k_; }
  Rng& rng() { return rng_; }

  void advance(PatchIndex j) {
    // Escape: scored where the kernel counts it as a scored stop (matrix kernel), else 0.
    if (j < 0) {
      if constexpr (K::kEscapeScores) X_ = W_ * t_->absorb_score[k_];
      done_ = true;
      return;
    }
    W_ *= t_->gather_weight[k_];
    k_ = static_cast<std::size_t>(j);
    roulette();
  }

 private:
  // Roulette stop at k: scored.
  void roulette() {
    if (roulette_uniform(rng_) >= t_->p[k_]) {
      X_ = W_ * t_->absorb_score[k_];
      done_ = true;
    }
  }
  const WalkTables* t_ = nullptr;
  std::size_t k_ = 0;
  Rgb W_ = Rgb::Ones(), X_ = Rgb::Zero();
  Rng rng_;
  bool done_ = false;
};

template <TransitionKernel K>
class GatherCollision {
 public:
  GatherCollision() = default;
  GatherCollision(const K& kernel, std::size_t i, const Rng& rng) : t_(&kernel.tables()), k_(i), rng_(rng) {
    visit();
  }
  bool done() const { return done_; }
  const Rgb& score() const { return X_; }
  std::size_t from() const { return k_; }
  Rng& rng() { return rng_; }

  void advance(PatchIndex j) {
    if (j < 0) {
      done_ = true;
      return;
    }
    W_ *= t_->gather_weight[k_];
    k_ = static_cast<std::size_t>(j);
    visit();
  }

 private:
  // Score the state visited, then roulette.
  void visit() {
    X_ += W_ * t_->E[k_];
    if (roulette_uniform(rng_) >= t_->p[k_]) done_ = true;
  }
  const WalkTables* t_ = nullptr;
  std::size_t k_ = 0;
  Rgb W_ = Rgb::Ones(), X_ = Rgb::Zero();
  Rng rng_;
  bool done_ = false;
};

template <TransitionKernel K>
class GatherExpectedValue {
 public:
  GatherExpectedValue() = default;
  GatherExpectedValue(const K& kernel, std::size_t i, const Rng& rng)
      : kernel_(&kernel), k_(i), X_(kernel.tables().E[i]), rng_(rng) {
    visit();
  }
  bool done() const { return done_; }
  const Rgb& score() const { return X_; }
  std::size_t from() const { return k_; }
  Rng& rng() { return rng_; }

  void advance(PatchIndex j) {
    if (awaiting_HE_) {
      awaiting_HE_ = false;
      X_ += W_ * kernel_->HE(k_, j);
      roulette();
      return;
    }
    if (j < 0) {
      done_ = true;
      return;
    }
    W_ *= kernel_->tables().gather_weight[k_];
    k_ = static_cast<std::size_t>(j);
    visit();
  }

 private:
  // Expected emission of the next step from k (first a sample request where the kernel samples it), then
  // roulette.
  void visit() {
    if constexpr (K::kHESampled) {
      awaiting_HE_ = true;
    } else {
      X_ += W_ * kernel_->HE(k_, kNoSample);
      roulette();
    }
  }
  void roulette() {
    if (roulette_uniform(rng_) >= kernel_->tables().p[k_]) done_ = true;
  }
  const K* kernel_ = nullptr;
  std::size_t k_ = 0;
  Rgb W_ = Rgb::Ones(), X_ = Rgb::Zero();
  Rng rng_;
  bool awaiting_HE_ = false;
  bool done_ = false;
};

// Runs one walk to its end, one destination sample at a time.
template <TransitionKernel K, class Walk>
void run_walk(const K& kernel, Walk& walk, WalkCounters& counters) {
  while (!walk.done()) walk.advance(kernel.sample(walk.from(), walk.rng(), counters));
}

// The score of one walk from patch i with stream rng (left advanced past the walk).
template <TransitionKernel K>
Rgb gather_walk(GatherEstimator estimator, const K& kernel, std::size_t i, Rng& rng, WalkCounters& counters) {
  auto run = [&](auto walk) {
    run_walk(kernel, walk, counters);
    rng = walk.rng();
    return Rgb(walk.score());
  };
  switch (estimator) {
    case GatherEstimator::absorption: return run(GatherAbsorption<K>(kernel, i, rng));
    case GatherEstimator::collision: return run(GatherCollision<K>(kernel, i, rng));
    case GatherEstimator::expected_value: return run(GatherExpectedValue<K>(kernel, i, rng));
  }
  return Rgb::Zero();
}

}  // namespace radwalk
