#include "walk/matrix_kernel.h"

#include <string>

#include "core/check.h"
#include "core/error.h"

namespace radwalk {

SparseF shooting_transfer(const RadiosityProblem& problem) {
  const Eigen::VectorXd& A = problem.area;
  RADWALK_CHECK_EQ(A.size(), problem.F.rows());  // one area per row of F
  RADWALK_CHECK_GT(A.minCoeff(), 0.0);           // validation refuses faces without area
  SparseF T = problem.F.transpose();
  for (Eigen::Index k = 0; k < T.rows(); ++k)
    for (SparseF::InnerIterator it(T, k); it; ++it)
      it.valueRef() = static_cast<float>(double(it.value()) * A(it.col()) / A(k));
  return T;
}

MatrixKernel::MatrixKernel(const RadiosityProblem& problem, const PatchRgb& E, std::vector<double> p,
                           WalkDirection direction)
    // (Each branch its own RowAliasTables: a conditional between problem.F and a SparseF value would copy F.)
    : rows_(direction == WalkDirection::gather ? RowAliasTables(problem.F) : RowAliasTables(shooting_transfer(problem))) {
  const std::size_t N = problem.size();
  RADWALK_CHECK_EQ(rows_.rows(), N);  // F, rho, E, p and the areas agree in size
  RADWALK_CHECK_EQ(static_cast<std::size_t>(problem.rho.rows()), N);
  RADWALK_CHECK_EQ(static_cast<std::size_t>(E.rows()), N);
  RADWALK_CHECK_EQ(p.size(), N);
  // Row scales n_k and row sums s_k (known: a destination sample is a stop with probability 1 - s_k / n_k).
  std::vector<double> n(N), s(N);
  for (std::size_t k = 0; k < N; ++k) {
    n[k] = rows_.row_scale(k);
    s[k] = rows_.row_sum(k);
  }
  tables_ = make_kernel_tables(problem.rho, E, std::move(p), std::move(n), std::move(s));
  // (H E)_k for the expected-value estimator.
  HE_.assign(N, Rgb::Zero());
  for (std::size_t k = 0; k < N; ++k) {
    Rgb s = Rgb::Zero();
    for (SparseF::InnerIterator it(problem.F, static_cast<Eigen::Index>(k)); it; ++it)
      s += double(it.value()) * tables_.E[static_cast<std::size_t>(it.col())];
    HE_[k] = tables_.rho[k] * s;
  }
}

}  // namespace radwalk
