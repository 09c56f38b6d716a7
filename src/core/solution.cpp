#include "core/solution.h"

namespace radwalk {

const char* to_string(SolveStatus status) {
  switch (status) {
    case SolveStatus::converged: return "converged";
    case SolveStatus::max_iterations: return "max-iterations";
    case SolveStatus::diverged: return "diverged";
    case SolveStatus::refused: return "refused";
  }
  return "unknown";
}

}  // namespace radwalk
