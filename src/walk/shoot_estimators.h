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
#include <array>
#include <vector>

#include "core/rng.h"
#include "walk/alias_table.h"
#include "walk/moment_terms.h"
#include "walk/transition_kernel.h"
#include "walk/walk_method.h"

namespace radwalk {

// Where particles are born and with what weight.
struct ShootSource {
  AliasTable birth;        // pi_i
  std::vector<Rgb> W0;     // A_i E_i / pi_i (0 where pi_i = 0)
  double power = 0;        // Phi = sum_i A_i sum_c E_ic; 0 means nothing is emitted (no particles needed)
};

// Throws InputError if sizes disagree or an E or an area is negative.
ShootSource make_shoot_source(const PatchRgb& E, const Eigen::VectorXd& area);

// The table every particle reads: rho_k / p_k (0 where p_k = 0), the weight factor of a particle surviving the
// roulette at k (it leaves k with weight W_in rho_k / p_k).
struct ShootWeights {
  std::vector<Rgb> survivor;
  explicit ShootWeights(const KernelTables& kernel);
};

// Each estimator is a class with Tables (what its particles read besides the kernel's data, built once per solve
// from KernelTables), moment_source (its second-moment source term c_j for the exact variance: moment_terms.h,
// walk_variance.h; m = t.m()) and Particle<K>, a state machine (the walk concept of walk_lockstep.h, as in
// gather_estimators.h):
//   constructed from (kernel, tables, source, rng): born (one uniform from the stream), waiting for its first
//   move;
//   done(), from(), rng() as for gathering walks;
//   advance(j, score) consumes the destination sample j of from(), calls score(j, power) for a score at j, and
//   runs up to the next request (after the roulette at j) or the end.
// A particle draws from its own stream only: birth, then per step the destination sample and the roulette.
// Each class is registered as EstimatorOf<its method> right after it, as in gather_estimators.h.
// ShootParticle is what every particle keeps and does: it leaves patch k with weight W; a destination sample j
// ends it at a stop (j < 0) or it arrives at j with weight W n_k; the roulette at j absorbs it with probability
// 1 - p_j, else it leaves j.
template <TransitionKernel K, class Tables>
class ShootParticle {
 public:
  ShootParticle() = default;
  ShootParticle(const K& kernel, const Tables& tables, const ShootSource& source, const Rng& rng)
      : kt_(&kernel.tables()), t_(&tables), rng_(rng) {
    k_ = source.birth.sample(rng_.uniform());
    W_ = source.W0[k_];
  }
  // Born on patch k with weight W (stratified emission: stratified_emission.h), its first ray made from the four
  // uniforms `first` (SampleRequest::u; the ray kernel) and every later draw from rng.
  ShootParticle(const K& kernel, const Tables& tables, std::size_t k, const Rgb& W, const Rng& rng,
                const std::array<float, 4>& first)
      : kt_(&kernel.tables()), t_(&tables), k_(k), W_(W), rng_(rng), first_(first), has_first_(true) {}
  bool done() const { return done_; }
  std::size_t from() const { return k_; }
  Rng& rng() { return rng_; }
  // The uniforms of the next ray when they are given (the first ray of a stratified particle), else nullptr.
  const float* uniforms() const { return has_first_ ? first_.data() : nullptr; }

 protected:
  // True if the particle arrives at j; false (and done) at a stop.
  bool arrives(PatchIndex j) {
    has_first_ = false;
    done_ = j < 0;
    return !done_;
  }
  Rgb arriving_weight() const { return W_ * kt_->n[k_]; }
  // True (and done) if the roulette at j absorbs the particle.
  bool absorbed_at(std::size_t j) {
    done_ = roulette_uniform(rng_) >= kt_->p[j];
    return done_;
  }
  void leave(std::size_t j, const Rgb& W) {
    W_ = W;
    k_ = j;
  }

  const KernelTables* kt_ = nullptr;
  const Tables* t_ = nullptr;
  std::size_t k_ = 0;
  Rgb W_ = Rgb::Zero();
  Rng rng_;
  std::array<float, 4> first_{};
  bool has_first_ = false;
  bool done_ = false;
};

struct ShootCollision {
  using Tables = ShootWeights;

  template <TransitionKernel K>
  class Particle : public ShootParticle<K, Tables> {
   public:
    using ShootParticle<K, Tables>::ShootParticle;
    template <class Score>
    void advance(PatchIndex j, Score&& score) {
      if (!this->arrives(j)) return;
      const auto jj = static_cast<std::size_t>(j);
      const Rgb W_in = this->arriving_weight();
      score(jj, Rgb(W_in * this->kt_->rho[jj]));
      if (!this->absorbed_at(jj)) this->leave(jj, W_in * this->t_->survivor[jj]);
    }
  };

  // c_j = rho_j^2 (1 + 2 m_j); var = E[Y^2] - (B - E)^2.
  static MomentSource moment_source(const MomentTerms& t) {
    return {(t.rho.array().square() * (1.0 + 2.0 * t.m().array())).matrix(), t.B - t.E};
  }
};
template <> struct EstimatorOf<WalkMethod::shoot_collision> { using type = ShootCollision; };

struct ShootAbsorption {
  struct Tables : ShootWeights {
    std::vector<Rgb> absorbed;  // rho_k / (1 - p_k) (0 where p_k = 1): the score factor of an absorption at k
    explicit Tables(const KernelTables& kernel);
  };

  template <TransitionKernel K>
  class Particle : public ShootParticle<K, Tables> {
   public:
    using ShootParticle<K, Tables>::ShootParticle;
    template <class Score>
    void advance(PatchIndex j, Score&& score) {
      if (!this->arrives(j)) return;
      const auto jj = static_cast<std::size_t>(j);
      const Rgb W_in = this->arriving_weight();
      if (this->absorbed_at(jj))
        score(jj, Rgb(W_in * this->t_->absorbed[jj]));
      else
        this->leave(jj, W_in * this->t_->survivor[jj]);
    }
  };

  // c_j = rho_j^2 / (1 - p_j); var = E[Y^2] - (B - E)^2.
  static MomentSource moment_source(const MomentTerms& t) {
    return {(t.rho.array().square() / (1.0 - t.p.array())).matrix(), t.B - t.E};
  }
};
template <> struct EstimatorOf<WalkMethod::shoot_absorption> { using type = ShootAbsorption; };

struct ShootSurvival {
  using Tables = ShootWeights;

  template <TransitionKernel K>
  class Particle : public ShootParticle<K, Tables> {
   public:
    using ShootParticle<K, Tables>::ShootParticle;
    template <class Score>
    void advance(PatchIndex j, Score&& score) {
      if (!this->arrives(j)) return;
      const auto jj = static_cast<std::size_t>(j);
      if (this->absorbed_at(jj)) return;
      this->leave(jj, this->arriving_weight() * this->t_->survivor[jj]);
      score(jj, this->W_);
    }
  };

  // c_j = rho_j^2 (1 + 2 m_j) / p_j; var = E[Y^2] - (B - E)^2.
  static MomentSource moment_source(const MomentTerms& t) {
    return {(t.rho.array().square() * (1.0 + 2.0 * t.m().array()) / t.p.array()).matrix(), t.B - t.E};
  }
};
template <> struct EstimatorOf<WalkMethod::shoot_survival> { using type = ShootSurvival; };

// Runs one particle to its end, one destination sample at a time, handing its scores to score(j, power).
template <TransitionKernel K, class Particle, class Score>
void run_particle(const K& kernel, Particle& particle, WalkCounters& counters, Score&& score) {
  while (!particle.done()) particle.advance(kernel.sample(particle.from(), particle.rng(), counters), score);
}

}  // namespace radwalk
