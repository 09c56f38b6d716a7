#pragma once
// Shooting (forward) random-walk estimators: one particle estimates the reflected power of every patch at once.
//
// Power P_j = A_j B_j obeys P = A.*E + diag(rho) F^T P (reciprocity A_i F_ij = A_j F_ji), so the power leaving
// patches is emission plus reflected power R_j = rho_j Q_j, with Q_j = sum_k F_kj P_k the power arriving at j.
// The emission is known; the particles estimate R, and B_j = E_j + R_j / A_j.
//
// Particle: born on patch i with probability pi_i = Phi_i / Phi, Phi_i = A_i sum_c E_ic (ShootSource), weight
// W = A_i E_i / pi_i per channel. From the patch k it leaves, it moves to j with probability F_kj / n_k
// (kernel.sample; an escape or back hit ends it), arriving with weight W_in = W n_k. At j it survives the roulette
// with probability p_j and leaves j with weight W_in rho_j / p_j, else it is absorbed at j.
// Expected arriving weight at j = Q_j (induction over leaving weights, whose expectation is P). Scores at the
// arrival on j, each with expectation rho_j Q_j = R_j given the arrival:
//   collision  every arrival:          W_in rho_j
//   absorption arrivals absorbed at j: W_in rho_j / (1 - p_j)   (probability 1 - p_j)
//   survival   arrivals surviving j:   W_in rho_j / p_j          (probability p_j; = the weight it leaves with)
// score(j, power) receives each score in W (power units); a patch's per-particle score is the sum of its scores
// from that particle.
#include <vector>

#include "core/rng.h"
#include "walk/alias_table.h"
#include "walk/transition_kernel.h"

namespace radwalk {

enum class ShootEstimator { collision, absorption, survival };

// Where particles are born and with what weight.
struct ShootSource {
  AliasTable birth;        // pi_i
  std::vector<Rgb> W0;     // A_i E_i / pi_i (0 where pi_i = 0)
  double power = 0;        // Phi = sum_i A_i sum_c E_ic; 0 means nothing is emitted (no particles needed)
};

// Throws InputError if sizes disagree or an E or an area is negative.
ShootSource make_shoot_source(const PatchRgb& E, const Eigen::VectorXd& area);

template <TransitionKernel K, class Score>
void shoot_collision(const K& kernel, const ShootSource& source, Rng& rng, WalkCounters& counters, Score&& score) {
  const WalkTables& t = kernel.tables();
  std::size_t k = source.birth.sample(rng.uniform());
  Rgb W = source.W0[k];
  for (;;) {
    const PatchIndex j = kernel.sample(k, rng, counters);
    if (j < 0) return;
    const auto jj = static_cast<std::size_t>(j);
    const Rgb W_in = W * t.n[k];
    score(jj, Rgb(W_in * t.rho[jj]));
    if (roulette_uniform(rng) >= t.p[jj]) return;
    W = W_in * t.rho_over_p[jj];
    k = jj;
  }
}

template <TransitionKernel K, class Score>
void shoot_absorption(const K& kernel, const ShootSource& source, Rng& rng, WalkCounters& counters, Score&& score) {
  const WalkTables& t = kernel.tables();
  std::size_t k = source.birth.sample(rng.uniform());
  Rgb W = source.W0[k];
  for (;;) {
    const PatchIndex j = kernel.sample(k, rng, counters);
    if (j < 0) return;
    const auto jj = static_cast<std::size_t>(j);
    const Rgb W_in = W * t.n[k];
    if (roulette_uniform(rng) >= t.p[jj]) {
      score(jj, Rgb(W_in * t.rho_over_1mp[jj]));
      return;
    }
    W = W_in * t.rho_over_p[jj];
    k = jj;
  }
}

template <TransitionKernel K, class Score>
void shoot_survival(const K& kernel, const ShootSource& source, Rng& rng, WalkCounters& counters, Score&& score) {
  const WalkTables& t = kernel.tables();
  std::size_t k = source.birth.sample(rng.uniform());
  Rgb W = source.W0[k];
  for (;;) {
    const PatchIndex j = kernel.sample(k, rng, counters);
    if (j < 0) return;
    const auto jj = static_cast<std::size_t>(j);
    if (roulette_uniform(rng) >= t.p[jj]) return;
    W = W * t.n[k] * t.rho_over_p[jj];
    score(jj, W);
    k = jj;
  }
}

template <TransitionKernel K, class Score>
void shoot_particle(ShootEstimator estimator, const K& kernel, const ShootSource& source, Rng& rng,
                    WalkCounters& counters, Score&& score) {
  switch (estimator) {
    case ShootEstimator::collision: return shoot_collision(kernel, source, rng, counters, score);
    case ShootEstimator::absorption: return shoot_absorption(kernel, source, rng, counters, score);
    case ShootEstimator::survival: return shoot_survival(kernel, source, rng, counters, score);
  }
}

}  // namespace radwalk
