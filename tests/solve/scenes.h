#pragma once
// Small radiosity problems with known answers, built directly as RadiosityProblem (no mesh, no ray tracing).
#include <Eigen/Dense>
#include <vector>

#include "core/rng.h"
#include "solve/problem.h"

namespace radwalk::test {

// Unit-cube view factors (docs/reference-data.md): opposite faces (C-11, X = Y = 1), faces sharing an edge (C-14).
inline constexpr double kOpposite = 0.199824896;
inline constexpr double kAdjacent = 0.200043776;

// Faces of the unit cube: 0 floor, 1 ceiling, 2 and 3 (x = 0, x = 1), 4 and 5 (z = 0, z = 1). Opposite pairs
// (0,1), (2,3), (4,5).
inline int opposite_face(int i) { return i ^ 1; }

// The unit cube, one patch per face, F scaled by f_scale (1: the exact closed form), rho the same on every face.
inline RadiosityProblem cube(const Rgb& rho, const PatchRgb& E, double f_scale = 1) {
  RadiosityProblem p;
  p.F.resize(6, 6);
  std::vector<Eigen::Triplet<float, std::int32_t>> t;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      if (j != i) t.emplace_back(i, j, float(f_scale * (j == opposite_face(i) ? kOpposite : kAdjacent)));
  p.F.setFromTriplets(t.begin(), t.end());
  p.rho.resize(6, 3);
  for (int i = 0; i < 6; ++i) p.rho.row(i) = rho.transpose();
  p.E = E;
  p.area = Eigen::VectorXd::Ones(6);
  return p;
}

// Every face emitting E (the furnace).
inline RadiosityProblem furnace(double rho, double E) {
  return cube(Rgb::Constant(rho), PatchRgb::Constant(6, 3, E));
}

// Only the ceiling (face 1) emitting.
inline RadiosityProblem lit_cube(const Rgb& rho, const Rgb& E_ceiling) {
  PatchRgb E = PatchRgb::Zero(6, 3);
  E.row(1) = E_ceiling.transpose();
  return cube(rho, E);
}

// Two parallel unit squares at distance 1, open to a black environment: F12 = F21 = kOpposite.
inline RadiosityProblem plates(const Rgb& rho1, const Rgb& rho2, const Rgb& E1, const Rgb& E2) {
  RadiosityProblem p;
  p.F.resize(2, 2);
  std::vector<Eigen::Triplet<float, std::int32_t>> t{{0, 1, float(kOpposite)}, {1, 0, float(kOpposite)}};
  p.F.setFromTriplets(t.begin(), t.end());
  p.rho.resize(2, 3);
  p.rho.row(0) = rho1.transpose();
  p.rho.row(1) = rho2.transpose();
  p.E.resize(2, 3);
  p.E.row(0) = E1.transpose();
  p.E.row(1) = E2.transpose();
  p.area = Eigen::VectorXd::Ones(2);
  return p;
}

// Inside a sphere cut into n patches of random areas: F_ij = A_j / A_total, including F_ii (a stored diagonal).
// Random rho per channel in [0.2, 0.8), a few emitters.
inline RadiosityProblem sphere(int n, std::uint64_t seed) {
  RadiosityProblem p;
  Rng rng(seed, 0);
  p.area.resize(n);
  for (int i = 0; i < n; ++i) p.area(i) = 0.5 + rng.uniform();
  const double total = p.area.sum();
  std::vector<Eigen::Triplet<float, std::int32_t>> t;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) t.emplace_back(i, j, float(p.area(j) / total));
  p.F.resize(n, n);
  p.F.setFromTriplets(t.begin(), t.end());
  p.rho.resize(n, 3);
  p.E = PatchRgb::Zero(n, 3);
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) p.rho(i, c) = 0.2 + 0.6 * rng.uniform();
    if (i % 7 == 0) p.E.row(i) = Rgb(10, 5, 1).transpose();
  }
  return p;
}

// The problem as a dense double matrix A_c = I - diag(rho_c) F.
inline Eigen::MatrixXd dense_system(const RadiosityProblem& p, int c) {
  const Eigen::MatrixXd F = Eigen::MatrixXd(p.F.cast<double>());
  return Eigen::MatrixXd::Identity(F.rows(), F.cols()) - p.rho.col(c).matrix().asDiagonal() * F;
}

// Reference: dense LU in double of each channel, independent of the library's direct solver.
inline PatchRgb dense_reference(const RadiosityProblem& p) {
  PatchRgb B(Eigen::Index(p.size()), 3);
  for (int c = 0; c < 3; ++c) B.col(c) = dense_system(p, c).partialPivLu().solve(p.E.col(c).matrix()).array();
  return B;
}

// kappa_inf(A_c) from the explicit inverse, max over channels.
inline double dense_condition(const RadiosityProblem& p) {
  double worst = 0;
  for (int c = 0; c < 3; ++c) {
    const Eigen::MatrixXd A = dense_system(p, c);
    const Eigen::MatrixXd inv = A.inverse();
    worst = std::max(worst, A.cwiseAbs().rowwise().sum().maxCoeff() * inv.cwiseAbs().rowwise().sum().maxCoeff());
  }
  return worst;
}

// ||X - Y||_inf / ||Y||_inf over all channels.
inline double relative_difference(const PatchRgb& X, const PatchRgb& Y) {
  return (X - Y).abs().maxCoeff() / Y.abs().maxCoeff();
}

}  // namespace radwalk::test
