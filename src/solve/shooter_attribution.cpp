#include "solve/shooter_attribution.h"

#include "core/check.h"
#include "core/error.h"
#include "core/timer.h"
#include "solve/block_jacobi.h"

namespace radwalk {

// The relative change at which the Jacobi sweeps of e^(r) and psi^(r) stop: c_j needs a few digits (it ranks), the
// identity (11) holds to about this over (1 - rho).
constexpr double kTolerance = 1e-7;

RowBlock adjoint_block(const RadiosityProblem& p, const RowBlock& W, long& sweeps) {
  const Eigen::Index N = static_cast<Eigen::Index>(p.size());
  RADWALK_CHECK_EQ(W.rows(), N);
  RADWALK_CHECK(W.cols() % 3 == 0);
  RADWALK_CHECK(p.row_blocks.empty());
  const Eigen::Index Q = W.cols() / 3;
  // psi = W + F^T (rho psi): F^T applied by scattering F's rows (row-major: a patch's columns contiguous).
  RowBlock psi = W, next(N, W.cols());
  Eigen::Array<double, 1, Eigen::Dynamic> source(W.cols());
  for (long sweep = 0;; ++sweep) {
    next = W;
    for (Eigen::Index i = 0; i < N; ++i) {
      for (Eigen::Index q = 0; q < Q; ++q)
        for (int c = 0; c < 3; ++c) source[3 * q + c] = p.rho(i, c) * psi(i, 3 * q + c);
      for (SparseF::InnerIterator it(p.F, i); it; ++it) next.row(it.col()) += double(it.value()) * source;
    }
    ++sweeps;
    const double change = (next - psi).abs().maxCoeff(), size = next.abs().maxCoeff();
    psi.swap(next);
    if (!(change > kTolerance * size)) break;
    if (sweep + 1 >= 100000)
      throw InputError("error estimate: the shooter attribution's adjoint did not converge in 100,000 sweeps "
                       "(spectral radius of diag(rho) F near 1)");
  }
  return psi;
}

ShooterAttribution shooter_attribution(const PatchSet& patches, const Visibility& visibility,
                                       const RadiosityProblem& h, const PatchRgb& B, const FluctuationSource& source,
                                       int directions, std::uint64_t seed) {
  const Timer timer;
  const Eigen::Index N = static_cast<Eigen::Index>(patches.size());
  RADWALK_CHECK_EQ(static_cast<Eigen::Index>(h.size()), N);
  RADWALK_CHECK_EQ(source.replicate[0].rows(), N);
  RADWALK_CHECK_EQ(source.replicate[1].rows(), N);
  ShooterAttribution out;
  // e^(r) = (I - H)^{-1} d^(r), both replicates in one block (columns 3 r + c).
  RowBlock Z(N, 6);
  for (int r = 0; r < 2; ++r) Z.middleCols(3 * r, 3) = source.replicate[r];
  const BlockSolution e = solve_block_jacobi(h, Z, kTolerance, "error estimate: the shooter attribution's solve");
  out.sweeps += e.sweeps;
  // psi^(r) = (I - H)^{-T} (A e^(r)).
  const RowBlock W = Eigen::Map<const Eigen::ArrayXd>(patches.area.data(), N).replicate(1, 6) * e.X;
  const RowBlock psi = adjoint_block(h, W, out.sweeps);
  // Replicate r's shots weighted by the other replicate's adjoint, halved.
  PatchRgb weights[2] = {psi.middleCols(3, 3) / 2, psi.middleCols(0, 3) / 2};
  out.share = weighted_fluctuation_shots(patches, visibility, B, source, weights, directions, seed);
  out.rays += source.shot_rays;  // traced again: the shots and the near targets' shadow rays
  for (Eigen::Index i = 0; i < N; ++i)
    out.total += patches.area[static_cast<std::size_t>(i)] * (e.X.row(i).segment(0, 3) * e.X.row(i).segment(3, 3)).sum();
  out.seconds = timer.seconds();
  return out;
}

}  // namespace radwalk
