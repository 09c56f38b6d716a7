#pragma once
// The terms the exact second moments of the random-walk estimators are made of (walk_variance.h), for one
// channel, over the rows walked with the matrix kernel: F for gathering, T = A^-1 F^T A for shooting
// (matrix_kernel.h). Each estimator turns them into its own source term c, in a static moment_source beside the
// estimator (gather_estimators.h, shoot_estimators.h), and names the mean its second moment is reduced by:
//   gathering  s = E[X^2] solves s = c + K s, K = diag(rho^2 n / p) F;     var = s - mean^2,
//   shooting   E[Y_j^2] = c_j r_j / A_j^2 (r from the birth term);         var = E[Y_j^2] - mean^2.
// Every shooting score at j carries the factor rho_j, so c_j = 0 where rho_j = 0 (the variance code zeroes it
// there, whatever moment_source returns).
#include <Eigen/Core>
#include <optional>

namespace radwalk {

struct MomentTerms {
  Eigen::VectorXd E, B, rho, p;  // emission, exact solution (same F), reflectance, survival
  Eigen::VectorXd q;             // q_k = 1 - p_k s_k / n_k: probability that a walk stops at k (roulette or escape)
  Eigen::VectorXd HE;            // g = H E = rho .* (F E): the expected emission of the next step from k
  const Eigen::MatrixXd* F = nullptr;  // the rows walked, dense

  // m_j = rho_j [(I - F diag(rho))^-1 F]_jj: the expected later score at j of a unit weight leaving j
  // (shooting). One dense LU, computed on first use.
  const Eigen::VectorXd& m() const;

 private:
  mutable std::optional<Eigen::VectorXd> m_;
};

// An estimator's second moment: its source term c and the mean that var = second moment - mean^2 subtracts.
struct MomentSource {
  Eigen::VectorXd c;
  Eigen::VectorXd mean;
};

}  // namespace radwalk
