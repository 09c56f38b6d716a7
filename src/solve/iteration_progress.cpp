#include "solve/iteration_progress.h"

#include <algorithm>
#include <cmath>

namespace radwalk {

IterationProgress::IterationProgress(std::string label, double tol, long budget, ProgressOutput output)
    : progress_(std::move(label), static_cast<std::size_t>(std::max(budget, 1L)), std::move(output)), tol_(tol),
      budget_(std::max(budget, 1L)) {}

void IterationProgress::update(long iterations, double residual) {
  if (first_iteration_ < 0 && std::isfinite(residual) && residual > 0) {
    first_iteration_ = iterations;
    first_residual_ = residual;
  }
  if (first_iteration_ >= 0 && iterations > first_iteration_ && std::isfinite(residual) && residual > 0 &&
      residual < first_residual_ && first_residual_ > tol_) {
    const double rate = std::log(first_residual_ / residual) / double(iterations - first_iteration_);
    const double total = double(first_iteration_) + std::log(first_residual_ / tol_) / rate;
    progress_.set_total(
        static_cast<std::size_t>(std::clamp(std::ceil(total), double(std::max(iterations, 1L)), double(budget_))));
  } else if (iterations < budget_) {
    progress_.set_total(Progress::kUnknownTotal);  // no rate yet: the budget would read as the length
  } else {
    progress_.set_total(static_cast<std::size_t>(budget_));
  }
  if (iterations > reported_) {
    progress_.advance(static_cast<std::size_t>(iterations - reported_));
    reported_ = iterations;
  }
}

}  // namespace radwalk
