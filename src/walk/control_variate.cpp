#include "walk/control_variate.h"

#include "core/check.h"

namespace radwalk {

ControlVariate constant_control_variate(const RadiosityProblem& problem) {
  const auto N = static_cast<Eigen::Index>(problem.size());
  RADWALK_CHECK(problem.F.rows() == N && problem.F.cols() == N);
  Eigen::VectorXd s = Eigen::VectorXd::Zero(N);  // s = F 1
  for (Eigen::Index i = 0; i < N; ++i)
    for (SparseF::InnerIterator it(problem.F, i); it; ++it) s(i) += static_cast<double>(it.value());
  ControlVariate cv;
  PatchRgb absorbed(N, 3);  // 1 - rho .* s
  for (Eigen::Index c = 0; c < 3; ++c) absorbed.col(c) = 1.0 - problem.rho.col(c) * s.array();
  for (int c = 0; c < 3; ++c) {
    const double emitted = (problem.area.array() * problem.E.col(c)).sum();
    const double denominator = (problem.area.array() * absorbed.col(c)).sum();
    cv.c(c) = denominator > 0 ? emitted / denominator : 0.0;  // no absorption anywhere: no finite B to shift by
  }
  cv.E_shifted = problem.E;
  for (int c = 0; c < 3; ++c) cv.E_shifted.col(c) -= cv.c(c) * absorbed.col(c);
  return cv;
}

}  // namespace radwalk
