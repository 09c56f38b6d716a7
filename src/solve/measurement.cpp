#include "solve/measurement.h"

#include <Eigen/SparseCore>
#include <cmath>

#include "core/check.h"
#include "core/error.h"
#include "core/timer.h"
#include "solve/direct_solver.h"

namespace radwalk {

void check_response(const Response& response, std::size_t patches) {
  const Eigen::VectorXd& R = response.R;
  if (static_cast<std::size_t>(R.size()) != patches)
    throw InputError("response " + response.what + ": " + std::to_string(R.size()) + " weights for " +
                     std::to_string(patches) + " patches");
  bool any = false;
  for (Eigen::Index i = 0; i < R.size(); ++i) {
    if (!std::isfinite(R(i)) || R(i) < 0)
      throw InputError("response " + response.what + ": weight " + number_text(R(i)) + " of patch " +
                       std::to_string(i) + " is not a finite number >= 0");
    any = any || R(i) > 0;
  }
  if (!any) throw InputError("response " + response.what + ": every weight is 0 (the measurement would be 0)");
}

Rgb measure(const Eigen::VectorXd& area, const Eigen::VectorXd& R, const PatchRgb& B) {
  RADWALK_CHECK_EQ(area.size(), R.size());
  RADWALK_CHECK_EQ(B.rows(), R.size());
  Rgb M = Rgb::Zero();
  for (Eigen::Index i = 0; i < R.size(); ++i)
    if (R(i) != 0) M += area(i) * R(i) * B.row(i).transpose();
  return M;
}

Rgb adjoint_measure(const Eigen::VectorXd& area, const PatchRgb& Y, const PatchRgb& E) {
  RADWALK_CHECK_EQ(Y.rows(), area.size());
  RADWALK_CHECK_EQ(E.rows(), area.size());
  Rgb M = Rgb::Zero();
  for (Eigen::Index i = 0; i < area.size(); ++i) M += area(i) * Y.row(i).transpose() * E.row(i).transpose();
  return M;
}

Solution solve_adjoint_direct(const RadiosityProblem& problem, const Response& response) {
  check_response(response, problem.size());
  Timer timer;
  const DirectSolver solver(problem);
  PatchRgb rhs(static_cast<Eigen::Index>(problem.size()), 3);
  for (int c = 0; c < 3; ++c) rhs.col(c) = (problem.area.array() * response.R.array());
  Solution s = solver.solve_transposed(problem, rhs);
  if (s.status == SolveStatus::refused) return s;
  for (int c = 0; c < 3; ++c) s.B.col(c) /= problem.area.array();  // Y = y / A
  s.seconds = timer.seconds();
  return s;
}

PatchRgb partial_radiosity(const RadiosityProblem& problem, int sweeps) {
  PatchRgb B = problem.E, term = problem.E;
  const Eigen::SparseMatrix<double, Eigen::RowMajor, int> F = problem.F.cast<double>();
  for (int m = 0; m < sweeps; ++m) {
    PatchRgb next(term.rows(), 3);
    for (int c = 0; c < 3; ++c) next.col(c) = problem.rho.col(c) * (F * term.col(c).matrix()).array();
    term = next;
    B += term;
  }
  return B;
}

PatchRgb partial_importance(const RadiosityProblem& problem, const Response& response, int sweeps) {
  check_response(response, problem.size());
  const Eigen::ArrayXd& A = problem.area.array();
  // y = A .* Y obeys y = A.*R + F^T diag(rho) y; sum its terms, then Y = y / A.
  PatchRgb y(static_cast<Eigen::Index>(problem.size()), 3), term;
  for (int c = 0; c < 3; ++c) y.col(c) = A * response.R.array();
  term = y;
  const Eigen::SparseMatrix<double, Eigen::RowMajor, int> Ft = problem.F.cast<double>().transpose();
  for (int m = 0; m < sweeps; ++m) {
    PatchRgb next(term.rows(), 3);
    for (int c = 0; c < 3; ++c) next.col(c) = (Ft * (problem.rho.col(c) * term.col(c)).matrix()).array();
    term = next;
    y += term;
  }
  for (int c = 0; c < 3; ++c) y.col(c) /= A;
  return y;
}

}  // namespace radwalk
