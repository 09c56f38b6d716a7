#include "solve/problem.h"

#include <cmath>
#include <string>

#include "core/check.h"
#include "core/error.h"

namespace radwalk {

RadiosityProblem make_problem(const PatchSet& patches, SparseF F, RowBlocks row_blocks) {
  const auto n = static_cast<Eigen::Index>(patches.size());
  // F comes from estimate_form_factors or from read_matrix_market, which refuses a file of another size.
  RADWALK_CHECK_EQ(F.rows(), n);
  RADWALK_CHECK_EQ(F.cols(), n);
  RadiosityProblem p;
  p.F = std::move(F);
  p.row_blocks = std::move(row_blocks);
  p.rho.resize(n, 3);
  p.E.resize(n, 3);
  p.area.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    p.rho.row(i) = patches.rho[i].transpose();
    p.E.row(i) = patches.E[i].transpose();
    p.area(i) = patches.area[i];
  }
  return p;
}

RadiosityProblem whole_problem(const RadiosityProblem& p) {
  RadiosityProblem whole = p;
  gather_whole_rows(whole.F, whole.row_blocks);
  return whole;
}

}  // namespace radwalk

namespace radwalk {

void check_problem(const RadiosityProblem& p) {
  // The arrays of one problem agree in size (make_problem builds them together); their values come from the
  // user's scene and form factors.
  const Eigen::Index n = p.area.size();
  RADWALK_CHECK_EQ(p.F.rows(), n);
  RADWALK_CHECK_EQ(p.F.cols(), n);
  RADWALK_CHECK_EQ(p.rho.rows(), n);
  RADWALK_CHECK_EQ(p.E.rows(), n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const std::string at = "patch " + std::to_string(i) + ": ";
    if (!std::isfinite(p.area(i)) || !(p.area(i) > 0))
      throw InputError(at + "area " + std::to_string(p.area(i)) + " must be finite and > 0");
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(p.rho(i, c)) || p.rho(i, c) < 0)
        throw InputError(at + "reflectance rho = " + std::to_string(p.rho(i, c)) + " must be finite and >= 0");
      if (!std::isfinite(p.E(i, c)) || p.E(i, c) < 0)
        throw InputError(at + "emission E = " + std::to_string(p.E(i, c)) + " must be finite and >= 0");
    }
    for (SparseF::InnerIterator it(p.F, i); it; ++it)
      if (!std::isfinite(it.value()) || it.value() < 0)
        throw InputError(at + "form factor F(" + std::to_string(i) + ", " + std::to_string(it.col()) +
                         ") = " + std::to_string(it.value()) + " must be finite and >= 0");
  }
}

}  // namespace radwalk
