#include "solve/exchange_discretisation.h"

#include <algorithm>
#include <cmath>

#include "solve/discretisation_error.h"
#include "visibility/embree_visibility.h"

namespace radwalk {

ExchangeDiscretisation exchange_discretisation(const PatchSet& patches, const RadiosityProblem& problem,
                                               const PatchRgb& B, const NetRadiationInput& input,
                                               const NetRadiationResult& r, int directions, std::uint64_t seed) {
  const std::size_t n = patches.size();
  const EmbreeVisibility visibility(patches);
  const DiscretisationError error = discretisation_error(patches, visibility, problem, B, directions, seed);
  ExchangeDiscretisation out;
  out.J.assign(n, 0.0);
  out.q.assign(n, 0.0);
  out.Q.assign(n, 0.0);
  out.T.assign(n, 0.0);
  const auto sd = [&](std::size_t i, int c) {
    const double e = error.estimate(Eigen::Index(i), c), s = error.standard_error(Eigen::Index(i), c);
    return std::sqrt(std::max(0.0, s * s - e * e));
  };
  for (std::size_t i = 0; i < n; ++i) {
    const double e = error.estimate(Eigen::Index(i), 0) - error.estimate(Eigen::Index(i), 1);
    const double s = sd(i, 0) + sd(i, 1);
    out.J[i] = std::sqrt(e * e + s * s);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const SurfaceCondition& c = input.surface[i];
    if (c.temperature_given) {
      if (c.emissivity < 1) {
        out.q[i] = c.emissivity / (1 - c.emissivity) * out.J[i];
      } else {
        double through = 0;
        for (SparseF::InnerIterator it(problem.F, Eigen::Index(i)); it; ++it)
          through += double(it.value()) * out.J[std::size_t(it.col())];
        out.q[i] = through;
      }
    } else if (r.T[i] > 0) {
      out.T[i] = out.J[i] / (4 * kStefanBoltzmann * r.T[i] * r.T[i] * r.T[i]);
    }
    out.Q[i] = patches.area[i] * out.q[i];
  }
  out.seconds = error.seconds;
  out.points = error.points;
  out.directions = error.directions;
  out.rays = error.rays;
  out.sweeps = error.sweeps;
  return out;
}

}  // namespace radwalk
