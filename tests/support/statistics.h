#pragma once
// Distributions for the hypothesis tests of the test suite (test-only: Boost.Math, which src/ does not use). Every
// Monte Carlo check states a family-wise significance level alpha, corrects it for the number m of simultaneous
// tests (Sidak: alpha_each = 1 - (1 - alpha)^(1/m)), and derives its tolerance from an estimated variance
// (docs/ARCHITECTURE.md, convention 7). The checks built on these are in stat_checks.h.
#include <cstddef>
#include <vector>

namespace radwalk {

// Per-test level so that m independent tests have family-wise level alpha: 1 - (1 - alpha)^(1/m).
double sidak(double alpha, std::size_t m);

// Two-sided critical value z such that P(|Z| > z) = alpha for a standard normal Z.
double z_critical(double alpha);

// Upper tail P(X > x) of a chi-square variable with dof degrees of freedom.
double chi_square_upper_tail(double x, double dof);

// Pearson chi-square goodness of fit: p-value of observed counts against expected counts (same length).
// Bins with expected count below 5 are pooled together (in order) before the test.
double chi_square_gof_p_value(const std::vector<double>& observed, const std::vector<double>& expected);

// Two-sided p-value for H0: sigma^2 = var_true, given a sample variance s2 from n samples, using the
// large-sample normal approximation Var(s2) = (mu4 - s2^2 (n-3)/(n-1)) / n with the sample fourth central
// moment mu4. Returns the z-score (s2 - var_true) / se(s2).
double variance_z_score(double s2, double var_true, double mu4, std::size_t n);

}  // namespace radwalk
