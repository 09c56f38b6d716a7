#pragma once
// Importance-driven random walks for one measurement of a linear system, with zero variance in the limit of
// exact importance (docs/theory/adjoint.md).
//
// System and measurement (one channel): x = s + K x with K >= 0 entrywise (sparse), s >= 0, and M = <r, x> =
// sum_i r_i x_i, r >= 0. Both walk directions of radwalk's measurements are of this form
// (walk/measure_walks.h):
//   from the sensor (adjoint, gathering):  x = B_c, s = E_c, K = diag(rho_c) F,       r = A.*R,  g ~ B_c;
//   from the sources (forward, shooting):  x = Y_c, s = R,   K = T diag(rho_c),       r = A.*E_c, g ~ Y_c,
//     T = A^-1 F^T A (walk/matrix_kernel.h), Y_c the importance of solve/measurement.h.
// Given an importance g >= 0 (an estimate of x) and a defensive fraction alpha in [0, 1], let
//   d_k = s_k + sum_j K_kj g_j,   n_k = max(1, sum_j K_kj)   (the analog chain's row scale),
// and the Markov chain
//   start       pi_i  = (1 - alpha) r_i g_i / <r, g> + alpha r_i / sum r,
//   move k->j   P_kj  = (1 - alpha) K_kj g_j / d_k  + alpha K_kj / n_k,
//   stop at k   q_k   = (1 - alpha) s_k / d_k       + alpha (1 - sum_j K_kj / n_k)       (sum_j P_kj + q_k = 1),
// (a term whose denominator is 0 is 0). A walk k_0 .. k_tau, stopped at k_tau, scores
//   Z = (r_k0 / pi_k0) prod_{m < tau} (K_{k_m k_m+1} / P_{k_m k_m+1}) (s_{k_tau} / q_{k_tau})      (absorption)
// which is unbiased, E[Z] = M, whenever P_kj > 0 where K_kj x_j > 0, q_k > 0 where s_k > 0 and pi_i > 0 where
// r_i x_i > 0 (alpha > 0 guarantees all three; so does alpha = 0 with g > 0 wherever x > 0).
//
// Zero variance with exact importance. Let alpha = 0 and g = x. Then d_k = s_k + (K x)_k = x_k, so
//   P_kj = K_kj x_j / x_k,  q_k = s_k / x_k,  pi_i = r_i x_i / M,
// and every path scores
//   Z = (r_k0 M / (r_k0 x_k0)) prod_m (x_{k_m} / x_{k_m+1}) (s_k_tau x_k_tau / s_k_tau) = M x_k0^-1 x_k0 = M
// (the product telescopes to x_k0 / x_k_tau). Every walk returns M exactly: the variance is 0 (up to rounding).
//
// Exact second moment (dense or sparse LU; finite iff the spectral radius of K2 is < 1): with
//   V_k = E[(Z from k)^2] = s_k^2 / q_k + sum_j (K_kj^2 / P_kj) V_j,  i.e. (I - K2) V = c,
//   E[Z^2] = sum_i r_i^2 V_i / pi_i,   var = E[Z^2] - M^2.
// With exact importance V_k = x_k^2 and E[Z^2] = M^2.
#include <Eigen/SparseCore>
#include <cstdint>
#include <vector>

#include "core/discrete_distribution.h"
#include "core/moments.h"
#include "core/rng.h"

namespace radwalk {

using SparseD = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

class ImportanceChain {
 public:
  // Throws InputError if sizes disagree, an entry of K, s, r or g is negative or not finite, alpha is outside
  // [0, 1], no start has positive probability, or a state with s_k > 0 or a non-empty row has no outcome.
  ImportanceChain(const SparseD& K, const Eigen::VectorXd& s, const Eigen::VectorXd& r, const Eigen::VectorXd& g,
                  double alpha);

  std::size_t size() const { return start_pdf_.size(); }

  // One walk from its own stream: Z as above; `steps` grows by the outcomes drawn. A walk that reaches a state with no outcome (d_k = 0 and
  // alpha = 0: x_k = 0 there) scores 0. NumericalError after kMaxSteps steps (the chain does not end).
  double walk(Rng& rng, long& steps) const;

  // E[Z^2] - M^2 from the linear system above, M = <r, x> with x solved from the same system (dense LU; N <=
  // kMaxTheoryPatches of walk_variance.h). +inf if the second moment is infinite (radius of K2 >= 1).
  double exact_variance() const;

  static constexpr long kMaxSteps = 100000000;

 private:
  struct Outcome {
    std::int32_t state;  // next state j, or -1: stop
    double factor;       // K_kj / P_kj, or s_k / q_k at a stop
  };
  SparseD K_;
  Eigen::VectorXd s_, r_;
  std::vector<double> start_pdf_, start_factor_;  // pi_i, r_i / pi_i
  AliasTable start_;
  std::vector<std::size_t> begin_;   // outcomes of state k: [begin_[k], begin_[k + 1])
  std::vector<Outcome> outcome_;
  std::vector<double> outcome_pdf_;  // P_kj or q_k of each outcome
  std::vector<AliasBucket> buckets_;
};

// Mean, per-walk variance and walks of `walks` walks of `chain` from the streams (seed, importance_walk,
// channel, w), w = 0 .. walks - 1, in fixed chunks merged in order (bit-identical for any thread count).
struct ChainEstimate {
  double mean = 0, var = 0, se = 0;
  long walks = 0;
  long steps = 0;  // transitions taken, stops included
};
ChainEstimate run_importance_walks(const ImportanceChain& chain, long walks, std::uint64_t seed, int channel);

}  // namespace radwalk
