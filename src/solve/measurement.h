#pragma once
// Measurements of a radiosity solution and the adjoint radiosity system (docs/theory/adjoint.md).
//
// A response R >= 0 over patches (a sensor: the patches of a desk, one patch, a camera's view) defines, per
// channel c, the measurement
//   M_c = <R, B_c>_A = sum_i A_i R_i B_ic,
// the area-weighted inner product <x, y>_A = sum_i A_i x_i y_i. With H_c = diag(rho_c) F and B_c = E_c + H_c B_c,
//   M_c = (A.*R)^T (I - H_c)^-1 E_c = y_c^T E_c = <Y_c, E_c>_A,
// where y_c = A.*Y_c solves the transposed (adjoint) system
//   (I - H_c)^T y_c = A.*R,  i.e.  y_c = A.*R + F^T diag(rho_c) y_c,
//   or for Y_c:  Y_c = R + A^-1 F^T diag(rho_c) A Y_c                                    (exact, any F)
//   which with reciprocity (A_i F_ij = A_j F_ji) is  Y_c = R + F diag(rho_c) Y_c.
// Y_c is the importance of each patch for the measurement: M_c = sum_i A_i E_ic Y_ic, so Y_ic is the response
// per unit of power emitted at i. Monte Carlo form factors are not reciprocal, so the exact transpose is solved.
#include <Eigen/Core>
#include <string>

#include "core/solution.h"
#include "core/types.h"
#include "solve/problem.h"

namespace radwalk {

struct Response {
  Eigen::VectorXd R;  // R_i >= 0 per patch, not all zero (dimensionless weights)
  std::string what;   // where it came from, in words ("material 'desk' (12 patches)", ...)
};

// Throws InputError (naming response.what) if R's size is not N, a weight is negative or not finite, or every
// weight is 0.
void check_response(const Response& response, std::size_t patches);

// M_c = sum_i A_i R_i B_ic per channel.
Rgb measure(const Eigen::VectorXd& area, const Eigen::VectorXd& R, const PatchRgb& B);

// <Y, E>_A = sum_i A_i Y_ic E_ic per channel: M from the adjoint solution Y.
Rgb adjoint_measure(const Eigen::VectorXd& area, const PatchRgb& Y, const PatchRgb& E);

// Y (N x 3, the importance) from the adjoint system above, by one LU of I - H_c per distinct rho column and a
// transposed substitution (DirectSolver::solve_transposed). Solution.B holds Y; status refused (with the direct
// solver's message) when the system is. Throws InputError for a bad problem or response.
Solution solve_adjoint_direct(const RadiosityProblem& problem, const Response& response);

// Cheap approximations of B and Y (importances for walk/importance_walk.h): the first `sweeps` + 1 terms of the
// Neumann series (Jacobi from 0),
//   B^(K) = sum_{m=0..K} (diag(rho_c) F)^m E_c,    Y^(K) = sum_{m=0..K} (A^-1 F^T diag(rho_c) A)^m R,
// which increase to B and Y as K grows (every term is >= 0). O(K nnz(F)).
PatchRgb partial_radiosity(const RadiosityProblem& problem, int sweeps);
PatchRgb partial_importance(const RadiosityProblem& problem, const Response& response, int sweeps);

}  // namespace radwalk
