#pragma once
// Enforcing reciprocity A_i F_ij = A_j F_ji on an estimated form-factor matrix.
//
// Each pair is replaced by its mean: A_i F'_ij = A_j F'_ji = (A_i F_ij + A_j F_ji) / 2 (so an entry hit from one
// side only becomes non-zero on both sides). A row whose sum would then exceed 1 is rescaled to sum exactly to 1
// (closure wins: F' stays substochastic; the pairs of that row keep a reciprocity error of at most its relative
// excess, reported as rows_rescaled and max_row_excess). In a closed scene about half the rows exceed 1 after
// averaging, by about the statistical error of the row sums, so reciprocity holds to that level there. Computed in double precision, stored back as float.
// Relative change of an entry: |F'_ij - F_ij| / max(F_ij, F'_ij), over the non-zeros of F'.
// Cost: O(nnz + N x slabs) time, F_ji read from F's transpose built a slab of columns at a time and merged with
// row i (formfactor/transpose_slabs.h: sequential memory access, no binary search); memory besides F and the
// result: 16 bytes per patch and at most max(nnz / 8, 2^20) transposed entries of 8 bytes (one byte per non-zero).
#include <cstddef>
#include <vector>

#include "formfactor/sparse_f.h"

namespace radwalk {

struct ReciprocityChange {
  double max_relative_change = 0;
  double mean_relative_change = 0;
  std::size_t rows_rescaled = 0;
  double max_row_excess = 0;  // largest (row sum - 1) after averaging, before rescaling (0 if none exceeded 1)
};

// InputError when an area is not finite and positive; InternalError (RADWALK_CHECK) when F is not square or area
// has the wrong size.
ReciprocityChange enforce_reciprocity(SparseF& F, const std::vector<double>& area);

}  // namespace radwalk
