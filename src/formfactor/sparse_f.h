#pragma once
// The form-factor matrix type: sparse, row-major (CSR), float values, 32-bit indices.
// Row i holds F_ij = fraction of the power leaving patch i diffusely that arrives at the front of patch j.
// Memory grows with the number of non-zeros, never with N^2.
#include <Eigen/SparseCore>
#include <cstdint>

namespace radwalk {

using SparseF = Eigen::SparseMatrix<float, Eigen::RowMajor, std::int32_t>;

}  // namespace radwalk
