#include "solve/direct_solver.h"

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <cmath>
#include <limits>
#include <vector>

#include "core/check.h"
#include "core/error.h"
#include "core/format_number.h"
#include "core/progress.h"
#include "core/timer.h"
#include "solve/residual.h"

namespace radwalk {

// Dense versus sparse LU, measured with bench_solvers (synthetic Monte Carlo-like F; 2 shared cores; seconds for
// the whole solve of 3 channels, peak extra memory):
//   rays/patch  N     dense LU         sparse LU (COLAMD)
//   1000        500   0.021 s   9 MB   0.047 s   18 MB
//   1000        1000  0.13 s   32 MB   0.17 s    57 MB
//   1000        2000  0.90 s  124 MB   1.05 s   178 MB
//   1000        4000  7.5 s   489 MB   12.1 s   608 MB
//   64          1000  0.13 s   33 MB   0.19 s    33 MB
//   64          4000  7.9 s   497 MB   21.0 s   557 MB
// Rows of a form-factor matrix couple patches across the whole scene, so sparse LU fills in almost completely and
// dense LU wins at every size measured. Dense up to 5000 (200 MB per factorisation), sparse above, where it only
// fits for genuinely local F.
const long kDenseMaxPatches = 5000;

namespace {

using SparseD = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

constexpr double kFloatEpsilon = 5.9604644775390625e-08;  // 2^-24, unit roundoff of the stored F

// ||I - diag(rho) F||_inf.
double infinity_norm(const SparseF& F, const Eigen::VectorXd& rho) {
  double worst = 0;
  for (Eigen::Index i = 0; i < F.rows(); ++i) {
    double sum = 0, diag = 0;
    for (SparseF::InnerIterator it(F, i); it; ++it) {
      if (it.col() == i) diag = rho(i) * it.value();
      else sum += rho(i) * it.value();
    }
    worst = std::max(worst, sum + std::abs(1 - diag));
  }
  return worst;
}

}  // namespace

struct DirectSolver::Impl {
  bool dense = true;
  bool ok = true;
  std::string message;
  double kappa = 0;
  double factor_seconds = 0;
  std::vector<int> group_of_channel = {0, 0, 0};  // which factorisation solves channel c
  std::vector<Eigen::PartialPivLU<Eigen::MatrixXd>> dense_lu;
  std::vector<std::unique_ptr<Eigen::SparseLU<SparseD, Eigen::COLAMDOrdering<int>>>> sparse_lu;

  Eigen::MatrixXd solve_group(int g, const Eigen::MatrixXd& rhs) const {
    if (dense) return dense_lu[std::size_t(g)].solve(rhs);
    return sparse_lu[std::size_t(g)]->solve(rhs);
  }
  // The transposed system of group g: (I - diag(rho) F)^T x = rhs.
  Eigen::MatrixXd solve_group_transposed(int g, const Eigen::MatrixXd& rhs) const {
    if (dense) return dense_lu[std::size_t(g)].transpose().solve(rhs);
    return sparse_lu[std::size_t(g)]->transpose().solve(rhs);
  }
};

DirectSolver::DirectSolver(const RadiosityProblem& p, DirectMethod method) : impl_(std::make_unique<Impl>()) {
  check_problem(p);
  Impl& m = *impl_;
  const Eigen::Index n = Eigen::Index(p.size());
  m.dense = method == DirectMethod::dense || (method == DirectMethod::automatic && n <= kDenseMaxPatches);
  Timer timer;

  // Channels that share rho share one factorisation.
  std::vector<int> representative;
  for (int c = 0; c < 3; ++c) {
    m.group_of_channel[std::size_t(c)] = int(representative.size());
    for (std::size_t g = 0; g < representative.size(); ++g)
      if ((p.rho.col(c) == p.rho.col(representative[g])).all()) m.group_of_channel[std::size_t(c)] = int(g);
    if (m.group_of_channel[std::size_t(c)] == int(representative.size())) representative.push_back(c);
  }

  if (n == 0) representative.clear();
  Progress progress("LU factorisations", representative.size());
  for (std::size_t g = 0; g < representative.size() && m.ok; ++g) {
    const int c = representative[g];
    const Eigen::VectorXd rho = p.rho.col(c).matrix();
    // Factorise A = I - diag(rho_c) F.
    if (m.dense) {
      Eigen::MatrixXd A = Eigen::MatrixXd::Identity(n, n);
      for (Eigen::Index i = 0; i < n; ++i)
        for (SparseF::InnerIterator it(p.F, i); it; ++it) A(i, it.col()) -= rho(i) * double(it.value());
      m.dense_lu.emplace_back(A);
    } else {
      std::vector<Eigen::Triplet<double>> t;
      t.reserve(std::size_t(p.F.nonZeros() + n));
      for (Eigen::Index i = 0; i < n; ++i) {
        t.emplace_back(int(i), int(i), 1.0);
        for (SparseF::InnerIterator it(p.F, i); it; ++it)
          t.emplace_back(int(i), int(it.col()), -rho(i) * double(it.value()));
      }
      SparseD A(n, n);
      A.setFromTriplets(t.begin(), t.end());  // sums the diagonal duplicates
      auto lu = std::make_unique<Eigen::SparseLU<SparseD, Eigen::COLAMDOrdering<int>>>();
      lu->compute(A);
      if (lu->info() != Eigen::Success) {
        m.ok = false;
        m.message = "direct solve refused: sparse LU found I - diag(rho) F singular for channel " +
                    std::to_string(c) + " (" + lu->lastErrorMessage() +
                    "): no finite radiosity exists. Check the reflectances (each must be < 1 where the scene is"
                    " closed) and the form factors (form-factor rows must sum to <= 1).";
        break;
      }
      m.sparse_lu.push_back(std::move(lu));
    }
    // Condition and solvability from x = A^{-1} 1 (see the header).
    const Eigen::VectorXd x = m.solve_group(int(g), Eigen::VectorXd::Ones(n));
    const double kappa = infinity_norm(p.F, rho) * x.maxCoeff();
    if (!x.allFinite() || !(x.minCoeff() > 0)) {
      m.ok = false;
      m.message =
          "direct solve refused: I - diag(rho) F is singular or not an M-matrix for channel " +
          std::to_string(c) + " ((I - H)^{-1} 1 has entries from " + format_number(x.minCoeff()) + " to " +
          format_number(x.maxCoeff()) +
          ", all must be >= 1): the spectral radius of diag(rho) F is >= 1, so no"
          " finite non-negative radiosity exists (max rho = " +
          format_number(rho.maxCoeff()) +
          "). Check the reflectances (each must be < 1 where the scene is closed) and the form factors"
          " (form-factor rows must sum to <= 1).";
      break;
    }
    if (!(kappa * kFloatEpsilon < 1)) {
      m.ok = false;
      m.message =
          "direct solve refused: I - diag(rho) F is numerically singular for channel " + std::to_string(c) +
          " (condition number " + format_number(kappa) +
          " >= 1/2^-24 = 1.7e7, so the float"
          " form factors determine no digit of B): the spectral radius of diag(rho) F is within rounding"
          " of 1. Check the reflectances (max rho = " +
          format_number(rho.maxCoeff()) + ").";
      break;
    }
    m.kappa = std::max(m.kappa, kappa);
    progress.advance(1);
  }
  progress.finish();
  if (!m.ok) m.kappa = std::numeric_limits<double>::infinity();
  m.factor_seconds = timer.seconds();
}

DirectSolver::~DirectSolver() = default;
DirectSolver::DirectSolver(DirectSolver&&) noexcept = default;
DirectSolver& DirectSolver::operator=(DirectSolver&&) noexcept = default;

bool DirectSolver::ok() const { return impl_->ok; }
const std::string& DirectSolver::message() const { return impl_->message; }
bool DirectSolver::dense() const { return impl_->dense; }
double DirectSolver::condition_estimate() const { return impl_->kappa; }
double DirectSolver::factor_seconds() const { return impl_->factor_seconds; }

Solution DirectSolver::solve(const RadiosityProblem& p) const {
  check_problem(p);
  const Impl& m = *impl_;
  Timer timer;
  Solution s;
  s.method = "direct";
  s.info["dense"] = m.dense ? 1 : 0;
  s.info["factor_seconds"] = m.factor_seconds;
  s.info["factorisations"] = double(m.dense ? m.dense_lu.size() : m.sparse_lu.size());
  if (!m.ok) {
    s.status = SolveStatus::refused;
    s.message = m.message;
    s.seconds = m.factor_seconds;
    return s;
  }
  const Eigen::Index n = Eigen::Index(p.size());
  Eigen::Index solver_n = 0;
  if (m.dense && !m.dense_lu.empty()) solver_n = m.dense_lu[0].rows();
  if (!m.dense && !m.sparse_lu.empty()) solver_n = m.sparse_lu[0]->rows();
  RADWALK_CHECK_EQ(solver_n, n);  // solve() takes the problem the solver was factorised for

  // Substitution per channel with its group's factors.
  s.B.resize(n, 3);
  for (int c = 0; c < 3 && n > 0; ++c)
    s.B.col(c) = m.solve_group(m.group_of_channel[std::size_t(c)], p.E.col(c).matrix()).array();
  s.residual = relative_residual(p, s.B);
  s.info["condition_estimate"] = m.kappa;
  s.info["condition_norm_inf"] = 1;  // the estimate is kappa_inf, exact (see direct_solver.h)
  s.seconds = m.factor_seconds + timer.seconds();
  s.message = std::string(m.dense ? "dense" : "sparse") + " LU of I - diag(rho) F (" +
              std::to_string(m.dense ? m.dense_lu.size() : m.sparse_lu.size()) +
              " factorisation(s)); relative residual " + format_number(s.residual) +
              ", condition number kappa_inf " + format_number(m.kappa) +
              ", so the solve's own (rounding) error of B is at most about " +
              format_number(m.kappa * s.residual) +
              " relative (the form factors' noise is a separate error, estimated apart)";
  if (!s.B.allFinite()) {  // cannot happen after the checks above; never hand out NaN
    s.status = SolveStatus::refused;
    s.message = "direct solve refused: the solution is not finite. " + s.message;
    s.B.resize(0, 3);
  }
  return s;
}

Solution DirectSolver::solve_transposed(const RadiosityProblem& p, const PatchRgb& rhs) const {
  const Impl& m = *impl_;
  const Eigen::Index n = Eigen::Index(p.size());
  RADWALK_CHECK_EQ(rhs.rows(), n);
  Timer timer;
  Solution s;
  s.method = "adjoint-direct";
  if (!m.ok) {
    s.status = SolveStatus::refused;
    s.message = m.message;
    return s;
  }
  s.B.resize(n, 3);
  for (int c = 0; c < 3 && n > 0; ++c)
    s.B.col(c) = m.solve_group_transposed(m.group_of_channel[std::size_t(c)], rhs.col(c).matrix()).array();
  s.seconds = m.factor_seconds + timer.seconds();
  s.message = std::string(m.dense ? "dense" : "sparse") + " LU of I - diag(rho) F, transposed substitution";
  if (!s.B.allFinite()) {
    s.status = SolveStatus::refused;
    s.message = "adjoint direct solve refused: the solution is not finite. " + s.message;
    s.B.resize(0, 3);
  }
  return s;
}

Solution solve_direct(const RadiosityProblem& p, const SolveOptions& options, DirectMethod method) {
  check_options(options);
  Timer timer;
  DirectSolver solver(p, method);
  Solution s = solver.solve(p);
  s.seconds = timer.seconds();
  if (options.record_history && std::isfinite(s.residual)) s.residual_history = {s.residual};
  return s;
}

}  // namespace radwalk
