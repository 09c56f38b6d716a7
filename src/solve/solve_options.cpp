#include "solve/solve_options.h"

#include <cmath>

#include "core/error.h"

namespace radwalk {

long default_max_iterations(const std::string& solver, std::size_t patches) {
  return solver == "southwell" ? 1000 * static_cast<long>(patches) : 10000;
}

void check_options(const SolveOptions& options) {
  if (!std::isfinite(options.tol) || !(options.tol > 0))
    throw InputError("solver tolerance " + number_text(options.tol) + " must be finite and > 0");
  if (options.max_iterations < 0)
    throw InputError("max-iterations " + std::to_string(options.max_iterations) + " must be >= 0");
  if (options.auto_direct_max_patches < 0)
    throw InputError("auto_direct_max_patches " + std::to_string(options.auto_direct_max_patches) + " must be >= 0");
}

}  // namespace radwalk
