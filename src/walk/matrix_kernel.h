#pragma once
// MatrixKernel: the transition kernel over a stored sparse F (transition_kernel.h), one alias table per row.
//
// sample(k) draws column j of row k with probability F_kj / n_k or kEscaped with the row deficit
// 1 - s_k / n_k, in O(1) (RowAliasTables); the row sums s_k are known (tables().s).
// HE(k, .) is exact: (H E)_k = rho_k sum_j F_kj E_j, precomputed (no sample drawn). Memory: 16 bytes per non-zero
// of F plus O(N). Walks run one at a time (kLanes = 1): an alias draw gains nothing from batching.
//
// Direction: gathering walks sample rows of F. Shooting particles sample rows of the power transfer
//   T = A^-1 F^T A,  T_kj = A_j F_jk / A_k,
// because P = A.*B obeys P = A.*E + diag(rho) T^T P for the system B = E + diag(rho) F B with any F; T = F
// exactly when F is reciprocal (A_i F_ij = A_j F_ji), and a stored F that is not (Monte Carlo form factors)
// still gives shooting estimates unbiased for the same B the direct solver computes.
#include <utility>

#include "solve/problem.h"
#include "walk/alias_table.h"
#include "walk/transition_kernel.h"
#include "walk/walk_method.h"

namespace radwalk {

// T = A^-1 F^T A (see above). Throws InputError if an area is not positive.
SparseF shooting_transfer(const RadiosityProblem& problem);

class MatrixKernel {
 public:
  static constexpr bool kHESampled = false;
  static constexpr std::size_t kLanes = 1;
  // p: survival probability per patch (survival_probabilities). Throws InputError on sizes that disagree.
  MatrixKernel(const RadiosityProblem& problem, std::vector<double> p,
               WalkDirection direction = WalkDirection::gather)
      : MatrixKernel(problem, problem.E, std::move(p), direction) {}
  // The same with E (N x 3) walked in place of problem.E: the shifted source of the control variate
  // (control_variate.h), with no copy of the problem (F is read, not copied).
  MatrixKernel(const RadiosityProblem& problem, const PatchRgb& E, std::vector<double> p, WalkDirection direction);

  std::size_t size() const { return rows_.rows(); }
  const KernelTables& tables() const { return tables_; }
  const RowAliasTables& rows() const { return rows_; }

  PatchIndex sample(std::size_t k, Rng& rng, WalkCounters& counters) const {
    ++counters.steps;
    const PatchIndex j = rows_.sample(k, rng.uniform());
    if (j < 0) ++counters.escapes;
    return j;
  }
  void sample(std::span<const SampleRequest> requests, std::span<PatchIndex> out, WalkCounters& counters) const {
    for (std::size_t r = 0; r < requests.size(); ++r) out[r] = sample(requests[r].k, *requests[r].rng, counters);
  }
  Rgb HE(std::size_t k, PatchIndex /*j*/) const { return HE_[k]; }

 private:
  RowAliasTables rows_;
  KernelTables tables_;
  std::vector<Rgb> HE_;
};

}  // namespace radwalk
