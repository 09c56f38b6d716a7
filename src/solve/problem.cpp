#include "solve/problem.h"

#include "core/error.h"

namespace radwalk {

RadiosityProblem make_problem(const PatchSet& patches, SparseF F) {
  const auto n = static_cast<Eigen::Index>(patches.size());
  if (F.rows() != n || F.cols() != n)
    throw InputError("form factors are " + std::to_string(F.rows()) + " x " + std::to_string(F.cols()) +
                     " but the scene has " + std::to_string(n) + " patches");
  RadiosityProblem p;
  p.F = std::move(F);
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

}  // namespace radwalk
