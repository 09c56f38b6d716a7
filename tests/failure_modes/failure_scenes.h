#pragma once
// Analytic problems for the failure-mode tests, built in code (no mesh, no ray tracing).
//
//  - complete(n, rho): n equal patches, each seeing the n - 1 others equally, F_ij = 1 / (n - 1) (j != i).
//    Rows sum to 1 exactly (with n = 5, F = 0.25 is exact in float), so the closed-scene algebra is exact:
//    uniform rho and E give B = E / (1 - rho), spectral radius rho, kappa_inf(I - H) = (1 + rho) / (1 - rho),
//    and with B^0 = E the Jacobi residual after k sweeps is rho^(k+1) ||E|| exactly.
//  - box(rho, faces, scale): the unit cube (closed forms of docs/reference-data.md, Howell C-11 and C-14) restricted to
//    `faces` (a face left out is an opening), F multiplied by `scale`, every face emitting E = 1.
#include <Eigen/Sparse>
#include <cmath>
#include <vector>

#include "solve/problem.h"

namespace radwalk::test {

inline constexpr double kOppositeFace = 0.199824896;
inline constexpr double kAdjacentFace = 0.200043776;

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

inline RadiosityProblem box(const Rgb& rho, const std::vector<int>& faces = {0, 1, 2, 3, 4, 5}, double scale = 1) {
  const auto n = static_cast<int>(faces.size());
  std::vector<Eigen::Triplet<float, std::int32_t>> t;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      if (a != b)
        t.emplace_back(a, b,
                       static_cast<float>(scale * ((faces[a] ^ 1) == faces[b] ? kOppositeFace : kAdjacentFace)));
  SparseF F(n, n);
  F.setFromTriplets(t.begin(), t.end());
  return uniform_problem(std::move(F), rho, 1.0);
}

}  // namespace radwalk::test
