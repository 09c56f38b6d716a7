#include "solve/error_propagation.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"
#include "core/rng.h"
#include "core/timer.h"
#include "solve/block_gmres.h"
#include "solve/block_jacobi.h"

namespace radwalk {
namespace {

// A standard normal deviate by the Box-Muller transform (two uniforms, one deviate: simple, and cheap against
// the sweeps).
double standard_normal(Rng& rng) {
  const double u1 = 1.0 - rng.uniform();  // in (0, 1]
  const double u2 = rng.uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
}

}  // namespace

PropagatedVariance propagate_gather_variance(const RadiosityProblem& p, const PatchRgb& gather_variance, int probes,
                                             std::uint64_t seed) {
  Timer timer;
  const Eigen::Index N = static_cast<Eigen::Index>(p.size());
  RADWALK_CHECK(probes >= 1);
  RADWALK_CHECK_EQ(gather_variance.rows(), N);
  const PatchRgb q = p.rho.square() * gather_variance;
  // Column 3k + c of Z and X: probe k, channel c.
  const Eigen::Index columns = 3 * Eigen::Index(probes);
  RowBlock Z(N, columns);
  for (int k = 0; k < probes; ++k) {
    Rng rng = stream(seed, StreamDomain::error_estimate, 1 + std::uint64_t(k), 0);
    for (Eigen::Index i = 0; i < N; ++i)
      for (int c = 0; c < 3; ++c) {
        // A variance that rounding left at or below 0 (or undefined) contributes nothing.
        const double z = standard_normal(rng);
        Z(i, 3 * k + c) = q(i, c) > 0 ? std::sqrt(q(i, c)) * z : 0.0;
      }
  }
  // x = G z for every probe and channel at once (solve/block_jacobi.h; collective over MPI).
  PropagatedVariance out;
  out.probes = probes;
  // Block Jacobi converges at the rate of the spectral radius; with re-radiating rows (rho = 1, the net-radiation
  // system) it is close to 1, and the block GMRES (block_gmres.h) converges in a few tens of iterations instead.
  const char* what = "error estimate: the propagation of the form factors' noise";
  const bool conservative_rows = p.rho.size() > 0 && p.rho.maxCoeff() >= 0.99 && p.row_blocks.empty();
  BlockSolution solved = conservative_rows ? solve_block_gmres(p, Z, 1e-6, what) : solve_block_jacobi(p, Z, 1e-6, what);
  out.sweeps = solved.sweeps;
  const RowBlock& X = solved.X;
  out.variance.resize(N, 3);
  for (Eigen::Index i = 0; i < N; ++i)
    for (int c = 0; c < 3; ++c) {
      double excess = 0;
      for (int k = 0; k < probes; ++k) excess += X(i, 3 * k + c) * X(i, 3 * k + c) - Z(i, 3 * k + c) * Z(i, 3 * k + c);
      out.variance(i, c) = std::max(q(i, c), q(i, c) + excess / probes);
    }
  out.seconds = timer.seconds();
  return out;
}

}  // namespace radwalk
