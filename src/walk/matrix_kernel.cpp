#include "walk/matrix_kernel.h"

#include <string>

#include "core/error.h"

namespace radwalk {

SparseF shooting_transfer(const RadiosityProblem& problem) {
  const Eigen::VectorXd& A = problem.area;
  if (A.size() != problem.F.rows() || !(A.minCoeff() > 0))
    throw InputError("shooting: needs one positive area per row of F (" + std::to_string(A.size()) + " areas, " +
                     std::to_string(problem.F.rows()) + " rows)");
  SparseF T = problem.F.transpose();
  for (Eigen::Index k = 0; k < T.rows(); ++k)
    for (SparseF::InnerIterator it(T, k); it; ++it)
      it.valueRef() = static_cast<float>(double(it.value()) * A(it.col()) / A(k));
  return T;
}

MatrixKernel::MatrixKernel(const RadiosityProblem& problem, std::vector<double> p, WalkDirection direction)
    : rows_(direction == WalkDirection::gather ? problem.F : shooting_transfer(problem)) {
  const std::size_t N = problem.size();
  if (rows_.rows() != N || static_cast<std::size_t>(problem.rho.rows()) != N ||
      static_cast<std::size_t>(problem.E.rows()) != N || p.size() != N)
    throw InputError("matrix kernel: F has " + std::to_string(rows_.rows()) + " rows, rho " +
                     std::to_string(problem.rho.rows()) + ", E " + std::to_string(problem.E.rows()) + ", p " +
                     std::to_string(p.size()) + ", area " + std::to_string(N) + ": sizes must agree");
  // Row scales n_k and row sums s_k (known: a destination sample is a stop with probability 1 - s_k / n_k).
  std::vector<double> n(N), s(N);
  for (std::size_t k = 0; k < N; ++k) {
    n[k] = rows_.row_scale(k);
    s[k] = rows_.row_sum(k);
  }
  tables_ = make_kernel_tables(problem.rho, problem.E, std::move(p), std::move(n), std::move(s));
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
