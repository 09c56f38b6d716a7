#include "formfactor/reciprocity.h"

#include <cmath>
#include <string>

#include "core/check.h"
#include "core/error.h"

namespace radwalk {

ReciprocityChange enforce_reciprocity(SparseF& F, const std::vector<double>& area) {
  const std::size_t N = std::size_t(F.rows());
  RADWALK_CHECK_EQ(F.cols(), F.rows());
  RADWALK_CHECK_EQ(area.size(), N);
  for (std::size_t i = 0; i < N; ++i)
    if (!(std::isfinite(area[i]) && area[i] > 0))
      throw InputError(locate("enforce_reciprocity", 0, long(i), "area " + std::to_string(area[i]) + " is not > 0"));

  // Step 1: the symmetric part of G = diag(A) F.
  using SparseD = Eigen::SparseMatrix<double, Eigen::RowMajor, std::int32_t>;
  const Eigen::VectorXd A = Eigen::Map<const Eigen::VectorXd>(area.data(), Eigen::Index(N));
  SparseD G = A.asDiagonal() * F.cast<double>();
  SparseD Gt = G.transpose();
  SparseD S = 0.5 * (G + Gt);
  G = SparseD();
  Gt = SparseD();

  // Step 2: back to F' = diag(A)^-1 S, rescaling rows above 1, measuring the change entry by entry.
  ReciprocityChange change;
  double change_sum = 0;
  std::size_t entries = 0;
  for (std::size_t i = 0; i < N; ++i) {
    double sum = 0;
    for (SparseD::InnerIterator it(S, Eigen::Index(i)); it; ++it) sum += (it.valueRef() /= area[i]);
    if (sum > 1.0) {
      for (SparseD::InnerIterator it(S, Eigen::Index(i)); it; ++it) it.valueRef() /= sum;
      ++change.rows_rescaled;
      change.max_row_excess = std::max(change.max_row_excess, sum - 1.0);
    }
    SparseF::InnerIterator old(F, Eigen::Index(i));
    for (SparseD::InnerIterator it(S, Eigen::Index(i)); it; ++it) {
      while (old && old.index() < it.index()) ++old;  // F's pattern is a subset of S's
      const double before = (old && old.index() == it.index()) ? double(old.value()) : 0.0;
      const double m = std::max(before, it.value());
      const double rel = m > 0 ? std::abs(it.value() - before) / m : 0.0;
      change.max_relative_change = std::max(change.max_relative_change, rel);
      change_sum += rel;
      ++entries;
    }
  }
  change.mean_relative_change = entries ? change_sum / double(entries) : 0.0;
  F = S.cast<float>();
  return change;
}

}  // namespace radwalk
