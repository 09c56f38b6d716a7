#pragma once
// Direct solve of (I - H_c) B_c = E_c, H_c = diag(rho_c) F, per channel c, by LU factorisation.
//
// One factorisation per distinct column of rho (once when the three channels share rho). Dense partial-pivoting
// LU up to kDenseMaxPatches patches, where it is faster than sparse LU (measured, see direct_solver.cpp); Eigen's
// SparseLU (COLAMD ordering) above. The factorisation is the expensive state a DirectSolver keeps, so new
// emissions E are solved for the price of a substitution.
//
// Condition estimate (Solution.info["condition_estimate"]): kappa_inf(I - H_c) = ||I - H_c||_inf * max_i x_i with
// x = (I - H_c)^{-1} 1, max over channels. It is exact, not a bound, because H_c >= 0 with radius < 1 makes
// (I - H_c)^{-1} = sum_k H_c^k >= 0 entrywise, so its infinity norm is its largest row sum, max_i x_i. The same x
// tests physical solvability: x > 0 holds iff I - H_c is a nonsingular M-matrix, i.e. iff radius(H_c) < 1.
// Refused (SolveStatus::refused, message) when the LU finds the matrix singular, when x is not positive
// (radius >= 1: no finite non-negative radiosity, e.g. rho = 1 on every patch of a closed scene), or when
// kappa * 2^-24 >= 1 (the float form factors then determine no digit of B).
#include <memory>

#include "solve/problem.h"
#include "core/solution.h"
#include "solve/solve_options.h"

namespace radwalk {

enum class DirectMethod { automatic, dense, sparse };

// Largest N for which DirectMethod::automatic uses dense LU.
extern const long kDenseMaxPatches;

class DirectSolver {
 public:
  // Factorises I - diag(rho_c) F for each distinct rho column, reporting progress ("LU factorisations", one item
  // per factorisation, core/progress.h). Throws InputError for a bad problem (check_problem).
  DirectSolver(const RadiosityProblem& p, DirectMethod method = DirectMethod::automatic);
  ~DirectSolver();
  DirectSolver(DirectSolver&&) noexcept;
  DirectSolver& operator=(DirectSolver&&) noexcept;

  // False when the system was refused; message() says why.
  bool ok() const;
  const std::string& message() const;
  bool dense() const;
  double condition_estimate() const;  // kappa_inf, max over channels (inf when refused)
  double factor_seconds() const;

  // B for emission E (N x 3) with the problem's F and rho; status refused (B empty) if the system was refused.
  Solution solve(const RadiosityProblem& p) const;

  // The transposed systems: y_c with (I - diag(rho_c) F)^T y_c = (I - F^T diag(rho_c)) y_c = rhs_c per channel,
  // by the same factorisation (the adjoint radiosity system, solve/adjoint_radiosity.h). rhs is N x 3. Status
  // refused (B empty) if the system was refused; Solution.B holds y.
  Solution solve_transposed(const RadiosityProblem& p, const PatchRgb& rhs) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// One-shot: DirectSolver(p).solve(p). options.tol is not used (reported residual is what the LU achieved).
Solution solve_direct(const RadiosityProblem& p, const SolveOptions& options = {},
                      DirectMethod method = DirectMethod::automatic);

}  // namespace radwalk
