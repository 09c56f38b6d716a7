#pragma once
// Analytic problems for the failure-mode tests, built in code (no mesh, no ray tracing).
//
//  - complete(n, rho): n equal patches, each seeing the n - 1 others equally, F_ij = 1 / (n - 1) (j != i).
//    Rows sum to 1 exactly (with n = 5, F = 0.25 is exact in float), so the closed-scene algebra is exact:
//    uniform rho and E give B = E / (1 - rho), spectral radius rho, kappa_inf(I - H) = (1 + rho) / (1 - rho),
//    and with B^0 = E the Jacobi residual after k sweeps is rho^(k+1) ||E|| exactly.
//  - box(rho, faces, scale): the unit cube of reference_problems.h (closed forms of docs/reference-data.md) restricted to `faces` (a face left out is an
//    opening), F multiplied by `scale`, every face emitting E = 1.
#include <Eigen/Sparse>
#include <cmath>
#include <vector>

#include "solve/problem.h"
#include "support/reference_problems.h"

namespace radwalk::test {

inline RadiosityProblem uniform_problem(SparseF F, const Rgb& rho, double E) {
  RadiosityProblem p;
  const auto n = F.rows();
  p.F = std::move(F);
  p.rho.resize(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) p.rho.row(i) = rho.transpose();
  p.E = PatchRgb::Constant(n, 3, E);
  p.area = Eigen::VectorXd::Ones(n);
  return p;
}

inline RadiosityProblem complete(int n, double rho, double E = 1.0) {
  std::vector<Eigen::Triplet<float, std::int32_t>> t;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      if (j != i) t.emplace_back(i, j, static_cast<float>(1.0 / (n - 1)));
  SparseF F(n, n);
  F.setFromTriplets(t.begin(), t.end());
  return uniform_problem(std::move(F), Rgb::Constant(rho), E);
}

inline RadiosityProblem box(const Rgb& rho, const std::vector<int>& faces = kCubeFaces, double scale = 1) {
  return uniform_problem(unit_cube_F(faces, scale), rho, 1.0);
}

}  // namespace radwalk::test
