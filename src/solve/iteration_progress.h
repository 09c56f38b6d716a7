#pragma once
// Progress (core/progress.h) of an iterative solve, whose length is not known in advance.
//
// The relative residual falls about geometrically, so after k iterations at residual r_k, from r_a at iteration
// a (the first one reported), the total is estimated at the rate observed so far:
//     total = a + (k - a) * log(r_a / tol) / log(r_a / r_k),
// kept between k and the budget; until the residual has fallen below r_a there is none (Progress::kUnknownTotal:
// the reports count the iterations), and at the budget the budget.
#include <string>

#include "core/progress.h"

namespace radwalk {

class IterationProgress {
 public:
  // `label` names the stage ("gauss-seidel sweeps"); tol > 0 is the target residual; budget >= 0 the most
  // iterations the solver will run; `output` where the reports go (tests pass their own).
  IterationProgress(std::string label, double tol, long budget, ProgressOutput output = ProgressOutput::standard());
  // `iterations` done so far, with relative residual `residual` (a non-finite residual only advances).
  void update(long iterations, double residual);
  void finish() { progress_.finish(); }

 private:
  Progress progress_;
  double tol_;
  long budget_;
  long first_iteration_ = -1;
  double first_residual_ = 0;
  long reported_ = 0;
};

}  // namespace radwalk
