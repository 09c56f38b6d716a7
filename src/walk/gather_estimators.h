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
//                  so E[Y] = (I - H)^-1 H E = B - E.
// Each returns the walk's score per channel and adds its steps to `counters`.
#include "core/rng.h"
#include "walk/transition_kernel.h"

namespace radwalk {

enum class GatherEstimator { absorption, collision, expected_value };

template <TransitionKernel K>
Rgb gather_absorption(const K& kernel, std::size_t i, Rng& rng, WalkCounters& counters) {
  const WalkTables& t = kernel.tables();
  std::size_t k = i;
  Rgb W = Rgb::Ones();
  for (;;) {
    // Roulette stop: scored.
    if (roulette_uniform(rng) >= t.p[k]) return W * t.absorb_score[k];
    const PatchIndex j = kernel.sample(k, rng, counters);
    // Escape: scored where the kernel counts it as a scored stop (matrix kernel), else 0.
    if (j < 0) return K::kEscapeScores ? Rgb(W * t.absorb_score[k]) : Rgb::Zero();
    W *= t.gather_weight[k];
    k = static_cast<std::size_t>(j);
  }
}

template <TransitionKernel K>
Rgb gather_collision(const K& kernel, std::size_t i, Rng& rng, WalkCounters& counters) {
  const WalkTables& t = kernel.tables();
  std::size_t k = i;
  Rgb W = Rgb::Ones(), X = Rgb::Zero();
  for (;;) {
    // Score every state visited, then roulette and move.
    X += W * t.E[k];
    if (roulette_uniform(rng) >= t.p[k]) return X;
    const PatchIndex j = kernel.sample(k, rng, counters);
    if (j < 0) return X;
    W *= t.gather_weight[k];
    k = static_cast<std::size_t>(j);
  }
}

template <TransitionKernel K>
Rgb gather_expected_value(const K& kernel, std::size_t i, Rng& rng, WalkCounters& counters) {
  const WalkTables& t = kernel.tables();
  std::size_t k = i;
  Rgb W = Rgb::Ones(), X = t.E[i];
  for (;;) {
    // Expected emission of the next step from k, then roulette and move.
    X += W * kernel.HE(k, rng, counters);
    if (roulette_uniform(rng) >= t.p[k]) return X;
    const PatchIndex j = kernel.sample(k, rng, counters);
    if (j < 0) return X;
    W *= t.gather_weight[k];
    k = static_cast<std::size_t>(j);
  }
}

template <TransitionKernel K>
Rgb gather_walk(GatherEstimator estimator, const K& kernel, std::size_t i, Rng& rng, WalkCounters& counters) {
  switch (estimator) {
    case GatherEstimator::absorption: return gather_absorption(kernel, i, rng, counters);
    case GatherEstimator::collision: return gather_collision(kernel, i, rng, counters);
    case GatherEstimator::expected_value: return gather_expected_value(kernel, i, rng, counters);
  }
  return Rgb::Zero();
}

}  // namespace radwalk
