#include "solve/error_propagation.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"
#include "core/distributed.h"
#include "core/error.h"
#include "core/rng.h"
#include "core/timer.h"
#include "formfactor/form_factor_rows.h"

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
  using Block = Eigen::Array<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  Block Z(N, columns);
  for (int k = 0; k < probes; ++k) {
    Rng rng = stream(seed, StreamDomain::error_estimate, 1 + std::uint64_t(k), 0);
    for (Eigen::Index i = 0; i < N; ++i)
      for (int c = 0; c < 3; ++c) Z(i, 3 * k + c) = std::sqrt(q(i, c)) * standard_normal(rng);
  }
  // Jacobi sweeps x <- z + H x (every probe and channel at once): each process updates the rows it holds of F
  // (its row block over MPI, all rows otherwise) and the new rows are shared, so every process ends with the same
  // x, bit for bit, whatever the number of processes.
  Block X = Z, next(N, columns);
  Eigen::Array<double, 1, Eigen::Dynamic> gathered(columns), rho_row(columns), updated(columns);
  const distributed::Range mine = own_rows(p.row_blocks, static_cast<std::size_t>(N));
  PropagatedVariance out;
  out.probes = probes;
  for (;;) {
    double change = 0, size = 0;
    for (auto i = static_cast<Eigen::Index>(mine.begin); i < static_cast<Eigen::Index>(mine.end); ++i) {
      gathered.setZero();
      for (SparseF::InnerIterator it(p.F, i); it; ++it) gathered += double(it.value()) * X.row(it.col());
      for (int k = 0; k < probes; ++k) rho_row.segment(3 * k, 3) = p.rho.row(i);
      updated = Z.row(i) + rho_row * gathered;
      change = std::max(change, (updated - X.row(i)).abs().maxCoeff());
      size = std::max(size, updated.abs().maxCoeff());
      next.row(i) = updated;
    }
    if (!p.row_blocks.empty())
      distributed::allgather_in_place(next.data(), sizeof(double) * std::size_t(columns), p.row_blocks);
    X.swap(next);
    change = distributed::max_over_ranks(change);
    size = distributed::max_over_ranks(size);
    ++out.sweeps;
    if (!(change > 1e-6 * size)) break;
    if (out.sweeps >= 10000)
      throw InputError("error estimate: the propagation of the form factors' noise did not converge in 10,000 "
                       "sweeps (spectral radius of diag(rho) F near 1)");
  }
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
