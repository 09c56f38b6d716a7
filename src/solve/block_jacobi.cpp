#include "solve/block_jacobi.h"

#include <algorithm>
#include <string>

#include "core/check.h"
#include "core/distributed.h"
#include "core/error.h"
#include "formfactor/form_factor_rows.h"
#include "solve/iteration_progress.h"

namespace radwalk {
namespace {

constexpr long kMaxBlockSweeps = 10000;

}  // namespace

BlockSolution solve_block_jacobi(const RadiosityProblem& p, const RowBlock& Z, double tolerance, const char* what) {
  const Eigen::Index N = static_cast<Eigen::Index>(p.size());
  const Eigen::Index columns = Z.cols();
  RADWALK_CHECK_EQ(Z.rows(), N);
  RADWALK_CHECK(columns % 3 == 0);
  BlockSolution out;
  out.X = Z;
  RowBlock next(N, columns);
  Eigen::Array<double, 1, Eigen::Dynamic> gathered(columns), rho_row(columns), updated(columns);
  const distributed::Range mine = own_rows(p.row_blocks, static_cast<std::size_t>(N));
  // The change falls about geometrically: the sweeps left are estimated from its rate (solve/iteration_progress.h).
  IterationProgress progress(std::string(what) + ", sweeps", tolerance, kMaxBlockSweeps);
  for (;;) {
    double change = 0, size = 0;
    for (auto i = static_cast<Eigen::Index>(mine.begin); i < static_cast<Eigen::Index>(mine.end); ++i) {
      gathered.setZero();
      for (SparseF::InnerIterator it(p.F, i); it; ++it) gathered += double(it.value()) * out.X.row(it.col());
      for (Eigen::Index k = 0; k < columns; k += 3) rho_row.segment(k, 3) = p.rho.row(i);
      updated = Z.row(i) + rho_row * gathered;
      change = std::max(change, (updated - out.X.row(i)).abs().maxCoeff());
      size = std::max(size, updated.abs().maxCoeff());
      next.row(i) = updated;
    }
    if (!p.row_blocks.empty())
      distributed::allgather_in_place(next.data(), sizeof(double) * std::size_t(columns), p.row_blocks);
    out.X.swap(next);
    change = distributed::max_over_ranks(change);
    size = distributed::max_over_ranks(size);
    ++out.sweeps;
    progress.update(out.sweeps, size > 0 ? change / size : 0.0);
    if (!(change > tolerance * size)) break;
    if (out.sweeps >= kMaxBlockSweeps)
      throw InputError(std::string(what) + " did not converge in 10,000 sweeps (spectral radius of diag(rho) F near 1)");
  }
  return out;
}

}  // namespace radwalk
