#pragma once
// Gathering (adjoint) random-walk estimators of B_i, one walk each, over any TransitionKernel.
//
// A walk starts at k_0 = i with weight W_0 = 1 (per channel). At state k_m it survives with probability p_k
// (roulette, roulette_uniform) and then moves to j with probability F_kj / n_k (kernel.sample); the survivor's weight
// is W_{m+1} = W_m w_k, w_k = rho_k n_k / p_k = H_kj / P_kj. It stops at k_tau by roulette or escape.
// All three are unbiased for B_i = E_i + sum_j H_ij B_j (per channel):
//   absorption     X = W_tau E_{k_tau} / q_{k_tau}, scored only at a "scored stop" of probability q_k:
//                  E[X_i] = q_i E_i / q_i + sum_j P_ij w_i E[X_j].              (von Neumann-Ulam)
//                  Where the kernel knows the row sums s_k (matrix kernel, transition_kernel.h) every stop is
//                  scored, roulette or escape: q_k = 1 - p_k s_k / n_k; where it does not (ray kernel) only the
//                  roulette stop is, q_k = 1 - p_k, and an escape scores 0 (still unbiased).
//   collision      X = sum_{m=0..tau} W_m E_{k_m}: E[X_i] = E_i + sum_j P_ij w_i E[X_j].   (Wasow)
//   expected value X = E_i + sum_{m=0..tau} W_m (H E)_{k_m}: scores at each state the expectation of the next
//                  step's emission (next-event estimation); with Y = X - E, E[Y_i] = (HE)_i + sum_j H_ij E[Y_j],
//                  so E[Y] = (I - H)^-1 H E = B - E. (H E)_k is kernel.HE(k, j), with j one extra destination
//                  sample drawn before the roulette where the kernel samples it (kHESampled).
//
// Each estimator is a class with
//   Tables        what its walks read besides the kernel's own data, built once per solve from the kernel's
//                 KernelTables (the weight factors w_k of GatherWeights, absorption's scores E_k / q_k);
//   moment_source its second-moment source term c_k for the exact variance (moment_terms.h, walk_variance.h);
//   Walk<K>       a small state machine (the walk of walk_lockstep.h), so that one code serves a walk run on its
//                 own (run_walk) and walks advanced in lockstep, many destination samples per kernel call:
//   constructed from (kernel, tables, i, rng): runs up to its first destination request or its end;
//   done()        true once the walk has stopped; score() is then X;
//   from(), rng() while not done: the patch whose destination sample it waits for, and its stream;
//   advance(j)    consumes that sample and runs up to the next request or the end.
// A walk draws from its own stream only, in the same order however it is driven: per state the roulette, then
// the destination sample (expected value with kHESampled: HE sample, roulette, destination sample).
// Each class is registered as EstimatorOf<its method> right after it, and its method is a row of kWalkMethods
// (walk_method.h); with_estimator (walk_estimators.h) dispatches to it.
#include <vector>

#include "core/rng.h"
#include "walk/moment_terms.h"
#include "walk/transition_kernel.h"
#include "walk/walk_method.h"

namespace radwalk {

// The table every gathering walk reads: its weight factors w_k = rho_k n_k / p_k (0 where p_k = 0), per channel.
struct GatherWeights {
  std::vector<Rgb> w;
  explicit GatherWeights(const KernelTables& kernel);
};

// What every gathering walk keeps and does, under the walk interface above: it is at patch k with weight W and
// score X; the roulette at k ends it with probability 1 - p_k; a destination sample j moves it on to j with
// weight W w_k, or ends it at a stop (j < 0).
template <TransitionKernel K, class Tables>
class GatherWalk {
 public:
  GatherWalk() = default;
  GatherWalk(const K& kernel, const Tables& tables, std::size_t i, const Rng& rng)
      : kernel_(&kernel), t_(&tables), k_(i), rng_(rng) {}
  bool done() const { return done_; }
  const Rgb& score() const { return X_; }
  std::size_t from() const { return k_; }
  Rng& rng() { return rng_; }
  // A hint (walk_lockstep.h), no effect on any value: the records the walk reads once at j (its emission, its
  // survival probability and, on its next move, its weight factor), asked for before they are needed.
  void prefetch(PatchIndex j) const {
    if (j < 0) return;
    const auto k = static_cast<std::size_t>(j);
    __builtin_prefetch(&t_->w[k]);
    __builtin_prefetch(&kernel_->tables().E[k]);
    __builtin_prefetch(&kernel_->tables().p[k]);
  }

 protected:
  // True if the roulette at k ends the walk.
  bool stopped_by_roulette() {
    done_ = roulette_uniform(rng_) >= kernel_->tables().p[k_];
    return done_;
  }
  // True if the walk moved on to j; false (and done) at a stop.
  bool moved(PatchIndex j) {
    done_ = j < 0;
    if (done_) return false;
    W_ *= t_->w[k_];
    k_ = static_cast<std::size_t>(j);
    return true;
  }

  const K* kernel_ = nullptr;
  const Tables* t_ = nullptr;
  std::size_t k_ = 0;
  Rgb W_ = Rgb::Ones(), X_ = Rgb::Zero();
  Rng rng_;
  bool done_ = false;
};

struct GatherAbsorption {
  struct Tables : GatherWeights {
    std::vector<Rgb> score;      // E_k / q_k (0 where E_k = 0): what a scored stop at k scores, times the weight
    bool escape_scores = false;  // an escape is a scored stop (the kernel knows s_k)
    explicit Tables(const KernelTables& kernel);
  };

  template <TransitionKernel K>
  class Walk : public GatherWalk<K, Tables> {
   public:
    Walk() = default;
    Walk(const K& kernel, const Tables& tables, std::size_t i, const Rng& rng)
        : GatherWalk<K, Tables>(kernel, tables, i, rng) {
      roulette();
    }
    void advance(PatchIndex j) {
      // Escape: scored where it is a scored stop (matrix kernel), else 0.
      if (j < 0 && this->t_->escape_scores) this->X_ = this->W_ * this->t_->score[this->k_];
      if (this->moved(j)) roulette();
    }

   private:
    // Roulette stop at k: scored.
    void roulette() {
      if (this->stopped_by_roulette()) this->X_ = this->W_ * this->t_->score[this->k_];
    }
  };

  // c_k = E_k^2 / q_k (0 where E_k = 0); var = s - B^2.
  static MomentSource moment_source(const MomentTerms& t) {
    Eigen::VectorXd c(t.E.size());
    for (Eigen::Index k = 0; k < c.size(); ++k) c(k) = t.E(k) != 0 ? t.E(k) * t.E(k) / t.q(k) : 0.0;
    return {c, t.B};
  }
};
template <> struct EstimatorOf<WalkMethod::gather_absorption> { using type = GatherAbsorption; };

struct GatherCollision {
  using Tables = GatherWeights;

  template <TransitionKernel K>
  class Walk : public GatherWalk<K, Tables> {
   public:
    Walk() = default;
    Walk(const K& kernel, const Tables& tables, std::size_t i, const Rng& rng)
        : GatherWalk<K, Tables>(kernel, tables, i, rng) {
      visit();
    }
    void advance(PatchIndex j) {
      if (this->moved(j)) visit();
    }

   private:
    // Score the state visited, then roulette.
    void visit() {
      this->X_ += this->W_ * this->kernel_->tables().E[this->k_];
      this->stopped_by_roulette();
    }
  };

  // c_k = E_k (2 B_k - E_k); var = s - B^2.
  static MomentSource moment_source(const MomentTerms& t) { return {t.E.cwiseProduct(2.0 * t.B - t.E), t.B}; }
};
template <> struct EstimatorOf<WalkMethod::gather_collision> { using type = GatherCollision; };

struct GatherExpectedValue {
  using Tables = GatherWeights;

  template <TransitionKernel K>
  class Walk : public GatherWalk<K, Tables> {
   public:
    Walk() = default;
    Walk(const K& kernel, const Tables& tables, std::size_t i, const Rng& rng)
        : GatherWalk<K, Tables>(kernel, tables, i, rng) {
      this->X_ = kernel.tables().E[i];
      visit();
    }
    void advance(PatchIndex j) {
      if (awaiting_HE_) {
        awaiting_HE_ = false;
        this->X_ += this->W_ * this->kernel_->HE(this->k_, j);
        this->stopped_by_roulette();
        return;
      }
      if (this->moved(j)) visit();
    }

   private:
    // Expected emission of the next step from k (first a sample request where the kernel samples it), then
    // roulette.
    void visit() {
      if constexpr (K::kHESampled) {
        awaiting_HE_ = true;
      } else {
        this->X_ += this->W_ * this->kernel_->HE(this->k_, kNoSample);
        this->stopped_by_roulette();
      }
    }
    bool awaiting_HE_ = false;
  };

  // s is the second moment of Y = X - E_i = sum_m W_m g_{k_m}: c_k = g_k (2 (B_k - E_k) - g_k), g = H E;
  // var = s - (B - E)^2.
  static MomentSource moment_source(const MomentTerms& t) {
    return {t.HE.cwiseProduct(2.0 * (t.B - t.E) - t.HE), t.B - t.E};
  }
};
template <> struct EstimatorOf<WalkMethod::gather_expected_value> { using type = GatherExpectedValue; };

// Runs one walk to its end, one destination sample at a time.
template <TransitionKernel K, class Walk>
void run_walk(const K& kernel, Walk& walk, WalkCounters& counters) {
  while (!walk.done()) walk.advance(kernel.sample(walk.from(), walk.rng(), counters));
}

}  // namespace radwalk
