#include "solve/distributed_sweeps.h"

namespace radwalk {

std::vector<distributed::Range> sweep_row_blocks(const RadiosityProblem& p) {
  const SparseF& F = p.F;
  const auto n = static_cast<std::size_t>(F.rows());
  if (distributed::size() == 1) return {distributed::Range{0, n}};
  if (holds_own_rows_only(p.row_blocks)) return p.row_blocks;
  // A sweep's cost per row: its non-zeros, and the row itself.
  std::vector<double> weights(n);
  for (Eigen::Index i = 0; i < F.rows(); ++i)
    weights[static_cast<std::size_t>(i)] =
        1.0 + (F.isCompressed() ? F.outerIndexPtr()[i + 1] - F.outerIndexPtr()[i] : F.innerNonZeroPtr()[i]);
  return distributed::weighted_blocks(weights);
}

void exchange_rows(PatchRgb& B, const std::vector<distributed::Range>& blocks) {
  if (distributed::size() == 1) return;
  // PatchRgb is row-major: a row is 3 consecutive doubles.
  distributed::allgather_in_place(B.data(), 3 * sizeof(double), blocks);
}

void exchange_rows(Eigen::VectorXd& x, const std::vector<distributed::Range>& blocks) {
  if (distributed::size() == 1) return;
  distributed::allgather_in_place(x.data(), sizeof(double), blocks);
}

}  // namespace radwalk
