#include "walk/moment_terms.h"

#include <Eigen/Dense>

#include "core/check.h"

namespace radwalk {

const Eigen::VectorXd& MomentTerms::m() const {
  if (!m_) {
    RADWALK_CHECK(F != nullptr);
    RADWALK_CHECK_EQ(F->rows(), rho.size());
    const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(F->rows(), F->cols());
    const Eigen::MatrixXd M = (I - *F * rho.asDiagonal()).partialPivLu().solve(*F);
    m_ = rho.cwiseProduct(M.diagonal());
  }
  return *m_;
}

}  // namespace radwalk
