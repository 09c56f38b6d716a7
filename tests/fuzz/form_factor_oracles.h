#pragma once
// The oracles of the form-factor file harnesses (fuzz_matrix_market.cpp, fuzz_npz.cpp) on an accepted matrix:
// the CSR invariants every reader promises (formfactor/matrix_market.h, formfactor/npz.h), and a round trip
// that gives the same matrix bit for bit.
#include <algorithm>
#include <cstring>
#include <string>

#include "formfactor/matrix_market.h"
#include "formfactor/sparse_f.h"
#include "fuzz_support.h"

namespace radwalk::fuzz {

// F is n x n, compressed, with offsets from 0 to nnz and monotone, columns in range and strictly increasing
// within each row, values in [0, 1] and row sums <= kMaxRowSum.
inline void check_form_factor_csr(const SparseF& F, std::size_t n) {
  RADWALK_FUZZ_CHECK(F.rows() == static_cast<Eigen::Index>(n) && F.cols() == F.rows(), "size");
  RADWALK_FUZZ_CHECK(F.isCompressed(), "not compressed");
  const std::int32_t* outer = F.outerIndexPtr();
  const std::int32_t* inner = F.innerIndexPtr();
  const float* value = F.valuePtr();
  RADWALK_FUZZ_CHECK(outer[0] == 0 && outer[n] == F.nonZeros(), "offsets do not span the entries");
  for (std::size_t i = 0; i < n; ++i) {
    const std::string row = "row " + std::to_string(i);
    RADWALK_FUZZ_CHECK(outer[i] <= outer[i + 1], row + ": offsets not monotone");
    double sum = 0;
    for (std::int32_t k = outer[i]; k < outer[i + 1]; ++k) {
      RADWALK_FUZZ_CHECK(inner[k] >= 0 && inner[k] < F.cols(), row + ": column out of range");
      RADWALK_FUZZ_CHECK(k == outer[i] || inner[k - 1] < inner[k], row + ": columns not strictly increasing");
      RADWALK_FUZZ_CHECK(value[k] >= 0 && value[k] <= 1, row + ": value outside [0, 1]");
      sum += value[k];
    }
    RADWALK_FUZZ_CHECK(sum <= kMaxRowSum, row + ": sums to more than 1 + 1e-3");
  }
}

// G (read back from what was written of F) is F: the same size, offsets, columns and bits of every value.
inline void check_same_matrix(const SparseF& F, const SparseF& G) {
  const auto nnz = static_cast<std::size_t>(F.nonZeros());
  RADWALK_FUZZ_CHECK(G.rows() == F.rows() && G.nonZeros() == F.nonZeros() && G.isCompressed(), "size changed");
  RADWALK_FUZZ_CHECK(std::equal(F.outerIndexPtr(), F.outerIndexPtr() + F.rows() + 1, G.outerIndexPtr()),
                     "offsets changed");
  RADWALK_FUZZ_CHECK(std::equal(F.innerIndexPtr(), F.innerIndexPtr() + nnz, G.innerIndexPtr()), "columns changed");
  RADWALK_FUZZ_CHECK(nnz == 0 || std::memcmp(F.valuePtr(), G.valuePtr(), nnz * sizeof(float)) == 0,
                     "values changed (not bit for bit)");
}

}  // namespace radwalk::fuzz
