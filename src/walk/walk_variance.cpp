#include "walk/walk_variance.h"

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"
#include "solve/spectral_radius.h"
#include "walk/matrix_kernel.h"
#include "walk/moment_terms.h"
#include "walk/walk_estimators.h"

namespace radwalk {
namespace {

void refuse_large(std::size_t N, const char* what) {
  if (N > kMaxTheoryPatches)
    throw InputError(std::string(what) + ": needs dense N x N algebra; refused for N = " + std::to_string(N) +
                     " patches (limit " + std::to_string(kMaxTheoryPatches) + ")");
}

// Row sums s_k and row scales n_k = max(s_k, 1) of F.
void row_sums(const SparseF& F, Eigen::VectorXd& s, Eigen::VectorXd& n) {
  s.setZero(F.rows());
  for (Eigen::Index k = 0; k < F.rows(); ++k)
    for (SparseF::InnerIterator it(F, k); it; ++it) s(k) += double(it.value());
  n = s.cwiseMax(1.0);
}

Eigen::VectorXd survival_vector(const RadiosityProblem& problem, const WalkOptions& options) {
  const std::vector<double> p = survival_probabilities(problem.rho, options.survival);
  return Eigen::Map<const Eigen::VectorXd>(p.data(), static_cast<Eigen::Index>(p.size()));
}

// rho_c^2 / p per patch (0 where p = 0).
Eigen::VectorXd rho2_over_p(const Eigen::VectorXd& rho, const Eigen::VectorXd& p) {
  Eigen::VectorXd d(rho.size());
  for (Eigen::Index k = 0; k < rho.size(); ++k) d(k) = p(k) > 0 ? rho(k) * rho(k) / p(k) : 0.0;
  return d;
}

}  // namespace

PatchRgb dense_radiosity(const RadiosityProblem& problem) {
  const std::size_t N = problem.size();
  refuse_large(N, "dense radiosity");
  const Eigen::MatrixXd F = Eigen::MatrixXd(problem.F.cast<double>());
  PatchRgb B(static_cast<Eigen::Index>(N), 3);
  for (int c = 0; c < 3; ++c) {
    const Eigen::MatrixXd A = Eigen::MatrixXd::Identity(F.rows(), F.cols()) - problem.rho.col(c).matrix().asDiagonal() * F;
    B.col(c) = A.partialPivLu().solve(problem.E.col(c).matrix()).array();
  }
  return B;
}

PatchRgb theoretical_variance(const RadiosityProblem& problem, const WalkOptions& options, const PatchRgb& B_exact) {
  const std::size_t N = problem.size();
  refuse_large(N, "theoretical variance");
  check_walk_options(options, N);
  const auto n_rows = static_cast<Eigen::Index>(N);
  PatchRgb var(n_rows, 3);
  if (!check_finite_variance(problem, options).finite()) {
    var.setConstant(std::numeric_limits<double>::infinity());
    return var;
  }
  // Gathering walks rows of F, shooting rows of T = A^-1 F^T A (matrix_kernel.h): call either F below.
  const bool gather = is_gathering(options.method);
  const SparseF F_walk = gather ? problem.F : shooting_transfer(problem);
  const Eigen::MatrixXd F = Eigen::MatrixXd(F_walk.cast<double>());
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n_rows, n_rows);
  const Eigen::VectorXd p = survival_vector(problem, options);
  Eigen::VectorXd s, n;
  row_sums(F_walk, s, n);
  // The estimator's source term c and mean (next to each estimator: moment_source), per channel.
  auto moment_source = [&](int c) {
    MomentTerms t;
    t.E = problem.E.col(c).matrix();
    t.B = B_exact.col(c).matrix();
    t.rho = problem.rho.col(c).matrix();
    t.p = p;
    t.q = (1.0 - (p.array() * s.array() / n.array())).matrix();
    t.HE = t.rho.cwiseProduct(F * t.E);
    t.F = &F;
    return with_estimator(options.method,
                          [&](auto method) { return decltype(method)::Estimator::moment_source(t); });
  };

  if (gather) {
    for (int c = 0; c < 3; ++c) {
      const Eigen::VectorXd rho = problem.rho.col(c).matrix();
      // K = diag(rho^2 n / p) F; second moments s = (I - K)^-1 c.
      const Eigen::MatrixXd K = rho2_over_p(rho, p).cwiseProduct(n).asDiagonal() * F;
      const MomentSource source = moment_source(c);
      const Eigen::VectorXd second = (I - K).partialPivLu().solve(source.c);
      var.col(c) = (second - source.mean.cwiseProduct(source.mean)).array();
    }
    return var;
  }

  // Shooting.
  Eigen::VectorXd Phi(n_rows);
  for (Eigen::Index i = 0; i < n_rows; ++i) Phi(i) = problem.area(i) * problem.E.row(i).sum();
  const double power = Phi.sum();
  if (!(power > 0)) {
    var.setZero();
    return var;
  }
  const Eigen::VectorXd pi = Phi / power;
  for (int c = 0; c < 3; ++c) {
    const Eigen::VectorXd rho = problem.rho.col(c).matrix(), E = problem.E.col(c).matrix();
    const Eigen::VectorXd D = rho2_over_p(rho, p);
    // v_i = S_i^2 / pi_i; x solves (I - N F D)^T x = v; r_j = sum_i x_i n_i F_ij.
    Eigen::VectorXd v = Eigen::VectorXd::Zero(n_rows);
    for (Eigen::Index i = 0; i < n_rows; ++i)
      if (pi(i) > 0) v(i) = std::pow(problem.area(i) * E(i), 2) / pi(i);
    const Eigen::MatrixXd NF = n.asDiagonal() * F;
    const Eigen::VectorXd x = (I - NF * D.asDiagonal()).transpose().partialPivLu().solve(v);
    const Eigen::VectorXd r = NF.transpose() * x;
    const MomentSource source = moment_source(c);
    for (Eigen::Index j = 0; j < n_rows; ++j) {
      const double cj = rho(j) > 0 ? source.c(j) : 0.0;  // every score at j carries rho_j (moment_terms.h)
      const double second = cj * r(j) / (problem.area(j) * problem.area(j));
      var(j, c) = second - source.mean(j) * source.mean(j);
    }
  }
  return var;
}

VarianceCheck check_finite_variance(const RadiosityProblem& problem, const WalkOptions& options) {
  VarianceCheck check;
  if (problem.size() == 0 || problem.F.rows() != static_cast<Eigen::Index>(problem.size())) return check;
  const Eigen::VectorXd p = survival_vector(problem, options);
  // Rows walked: F (gathering, or the ray kernel's exact F) or T = A^-1 F^T A (matrix shooting).
  RadiosityProblem K;
  K.F = !is_gathering(options.method) && options.kernel == WalkKernel::matrix ? shooting_transfer(problem) : problem.F;
  Eigen::VectorXd s, n;
  row_sums(K.F, s, n);
  if (options.kernel == WalkKernel::ray) n.setOnes();
  // K_c = diag(rho_c^2 n / p) F is diag(rho') F with rho' = rho^2 n / p: reuse the radius of H.
  K.area = problem.area;
  K.E = problem.E;
  K.rho.resize(problem.rho.rows(), 3);
  for (int c = 0; c < 3; ++c) K.rho.col(c) = rho2_over_p(problem.rho.col(c).matrix(), p).cwiseProduct(n).array();
  const SpectralRadius r = estimate_spectral_radius(K, 300, 1e-4);
  check.radius = r.estimate;
  check.upper = r.upper;
  check.channel = r.channel;
  return check;
}

}  // namespace radwalk
