#pragma once
// The form-factor matrix type: sparse, row-major (CSR), float values, 32-bit indices.
// Row i holds F_ij = fraction of the power leaving patch i diffusely that arrives at the front of patch j.
// Memory grows with the number of non-zeros, never with N^2.
//
// Eigen 3.4's SparseMatrix has no move constructor and no move assignment, so std::move(F) and returning F into
// an existing variable copy every non-zero (8 bytes each: at 10^6 patches and 1000 rays per patch, 6.4 GB more
// at the peak). SparseF is Eigen's matrix with both added, by swapping the arrays (O(1), no allocation); the
// moved-from matrix is left empty (0 x 0). Everything else is Eigen's.
#include <Eigen/SparseCore>
#include <cstdint>

namespace radwalk {

class SparseF : public Eigen::SparseMatrix<float, Eigen::RowMajor, std::int32_t> {
 public:
  using Base = Eigen::SparseMatrix<float, Eigen::RowMajor, std::int32_t>;

  SparseF() = default;
  SparseF(Eigen::Index rows, Eigen::Index cols) : Base(rows, cols) {}
  // From any sparse expression (a transpose, a product, a plain Eigen matrix): evaluated, as Eigen does.
  template <class Other>
  SparseF(const Eigen::SparseMatrixBase<Other>& other) : Base(other) {}  // NOLINT: implicit, like Eigen's
  SparseF(const SparseF& other) = default;
  SparseF(SparseF&& other) noexcept { swap(other); }

  SparseF& operator=(const SparseF& other) = default;
  SparseF& operator=(SparseF&& other) noexcept {
    Base released;  // this matrix's old arrays, freed when the call returns
    swap(released);
    swap(other);
    return *this;
  }
  // From any expression Eigen's matrix takes (sparse expressions, a plain Eigen matrix): Eigen's own overload.
  template <class Other>
  SparseF& operator=(const Other& other) {
    Base::operator=(other);
    return *this;
  }
};

}  // namespace radwalk
