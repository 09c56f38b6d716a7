#pragma once
// Enforcing closure and reciprocity together on an estimated form-factor matrix of a closed scene: the
// least-squares adjustment of the exchange areas X_ij = A_i F_ij (derivation: docs/theory/closure.md).
//
// The traced exchange areas are first symmetrised, m_ij = (A_i F_ij + A_j F_ji) / 2 over the union of the two
// patterns. The adjusted X' is the symmetric matrix on that pattern that minimises the variance-weighted squared
// change
//   (1/2) sum_{pairs p = {i, j}} (X'_p - m_p)^2 / (m_p s_p),   s_ij = (A_i/n_i + A_j/n_j) / 4, s_ii = A_i / n_i
// (m_p s_p is, to first order, the variance of m_p from the rays: Var(A_i F_ij) = A_i^2 F_ij / n_i) subject to
// closure, sum_j X'_ij = A_i for every i. The Lagrange conditions give the multiplicative correction
//   X'_ij = m_ij (1 + s_ij (lambda_i + lambda_j)),   X'_ii = m_ii (1 + s_ii lambda_i),
// so zeros stay zero (the pattern is kept) and the multipliers solve the symmetric positive semi-definite system
//   sum_j m_ij s_ij (lambda_i + lambda_j) + m_ii s_ii lambda_i = A_i - sum_j m_ij   (one row per patch),
// solved by conjugate gradients (Jacobi preconditioner). An entry that would become negative is set to 0 and the
// system solved again without it (an active set, at most kClosureActiveSetRounds rounds); entries are never
// negative. Without ray counts (analytic or read F) every n_i is taken as 1 (weights from the areas alone).
// F'_ij = X'_ij / A_i, computed in double and stored as float: closure and reciprocity then hold to float rounding.
// Cost: O(nnz) per conjugate-gradient iteration; memory besides F: three double copies of the exchange areas
// (12 bytes per non-zero each) and the Lagrange matrix; F' has the union of the patterns of F and F^T.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "formfactor/sparse_f.h"

namespace radwalk {

inline constexpr int kClosureActiveSetRounds = 20;

struct ClosureChange {
  // Per row i over the entries of its (symmetrised) pattern: max_j |F'_ij - F_ij| and sqrt(mean_j (F'_ij - F_ij)^2).
  std::vector<double> row_max_change, row_rms_change;
  double max_change = 0;          // the largest |F'_ij - F_ij|
  double rms_change = 0;          // sqrt(mean of (F'_ij - F_ij)^2) over all entries of the pattern
  double max_row_defect_before = 0;  // max_i |1 - sum_j F_ij| of the traced F
  double max_row_defect_after = 0;   // the same of F' (float rounding)
  double max_reciprocity_defect_after = 0;  // max |A_i F'_ij - A_j F'_ji| / max(A_i F'_ij, A_j F'_ji)
  std::size_t clipped = 0;        // pairs set to 0 by the active set (they would have become negative)
  int rounds = 0;                 // active-set rounds (1: no entry clipped)
  long cg_iterations = 0;         // conjugate-gradient iterations of the last round
  double cg_error = 0;            // its relative residual
};

// Adjusts F (N x N, every row) in place as above. rays: n_i per row (empty: all 1). Throws InputError naming the
// patch when an area is not finite and positive or a row of positive area has no entry (it sees nothing: no
// closed adjustment exists), and when the active set does not settle within kClosureActiveSetRounds rounds.
ClosureChange enforce_closure(SparseF& F, const std::vector<double>& area, const std::vector<std::uint32_t>& rays);

}  // namespace radwalk
