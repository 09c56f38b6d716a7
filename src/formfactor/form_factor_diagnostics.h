#pragma once
// Diagnostics of an estimated form-factor matrix F (row i = where rays leaving patch i land).
//
// Per patch i (vectors of length N):
//   row_sum[i]           = sum_j F_ij  (closure: 1 in a closed scene, 1 - escaped/n_i - back_hits/n_i in general)
//   back_hit_fraction[i] = back_hits_i / n_i                       (empty when no ray counts are given)
//   reciprocity_error[i] = max_j |A_i F_ij - A_j F_ji| / max(A_i F_ij, A_j F_ji) over j with F_ij or F_ji > 0
//                          (0 for a row with no such j; 1 where only one of the pair was ever hit)
//   row_std_error[i]     = sqrt(max_j F_ij (1 - F_ij) / n_i): the largest binomial standard error of an entry of
//                          row i, an upper bound for the stratified estimator's (see form_factors.h)
//                          (empty when no ray counts are given)
// Cost: O(nnz + N x slabs) time: row i of F merged with row i of F^T, the transpose built a slab of columns at a
// time (formfactor/transpose_slabs.h: sequential memory access, no binary search per entry); memory besides the
// outputs: 8 bytes per patch and at most max(nnz / 8, 2^20) transposed entries of 8 bytes (one byte per non-zero).
#include <cstdint>
#include <vector>

#include "formfactor/sparse_f.h"

namespace radwalk {

struct FormFactorDiagnostics {
  std::vector<double> row_sum, back_hit_fraction, reciprocity_error, row_std_error;
};

// `area` has N entries; `rays` and `back_hits` are either empty or have N entries (from FormFactors).
// Sizes that disagree with F are InternalError (RADWALK_CHECK).
FormFactorDiagnostics diagnose_form_factors(const SparseF& F, const std::vector<double>& area,
                                            const std::vector<std::uint32_t>& rays = {},
                                            const std::vector<std::uint32_t>& back_hits = {});

}  // namespace radwalk
