#include "solve/block_gmres.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/check.h"
#include "core/error.h"
#include "solve/iteration_progress.h"

namespace radwalk {
namespace {

constexpr long kMaxBlockGmresIterations = 10000;

using RowArray = Eigen::Array<double, 1, Eigen::Dynamic>;

// The splitting A = M - U, M = D - L, per column (rho of the column's channel), over F's raw compressed rows.
class BlockSplitting {
 public:
  BlockSplitting(const RadiosityProblem& p, Eigen::Index columns) : F_(p.F), rho_(p.F.rows(), columns),
                                                                      D_(p.F.rows(), columns) {
    const Eigen::Index n = F_.rows();
    split_.resize(std::size_t(n));
    for (Eigen::Index i = 0; i < n; ++i) {
      double diagonal = 0;
      auto k = F_.outerIndexPtr()[i];
      const auto end = F_.outerIndexPtr()[i + 1];
      while (k < end && F_.innerIndexPtr()[k] < i) ++k;
      if (k < end && F_.innerIndexPtr()[k] == i) diagonal = F_.valuePtr()[k++];
      split_[std::size_t(i)] = k;
      for (Eigen::Index c = 0; c < columns; ++c) {
        rho_(i, c) = p.rho(i, c % 3);
        D_(i, c) = 1 - rho_(i, c) * diagonal;
      }
    }
  }

  // Z = M^-1 V: Z_i = (V_i + rho_i sum_{j<i} F_ij Z_j) / D_i.
  void forward(const RowBlock& V, RowBlock& Z) const {
    RowArray lower(V.cols());
    for (Eigen::Index i = 0; i < F_.rows(); ++i) {
      lower.setZero();
      for (auto k = F_.outerIndexPtr()[i]; k < split_[std::size_t(i)]; ++k)
        if (F_.innerIndexPtr()[k] < i) lower += double(F_.valuePtr()[k]) * Z.row(F_.innerIndexPtr()[k]);
      Z.row(i) = (V.row(i) + rho_.row(i) * lower) / D_.row(i);
    }
  }

  // W = A M^-1 V = V - U M^-1 V (Z = M^-1 V as a by-product).
  void apply(const RowBlock& V, RowBlock& Z, RowBlock& W) const {
    forward(V, Z);
    RowArray upper(V.cols());
    for (Eigen::Index i = 0; i < F_.rows(); ++i) {
      upper.setZero();
      for (auto k = split_[std::size_t(i)]; k < F_.outerIndexPtr()[i + 1]; ++k)
        upper += double(F_.valuePtr()[k]) * Z.row(F_.innerIndexPtr()[k]);
      W.row(i) = V.row(i) - rho_.row(i) * upper;
    }
  }

  // R = B - A X = B - X + rho .* (F X).
  void residual(const RowBlock& B, const RowBlock& X, RowBlock& R) const {
    RowArray gathered(X.cols());
    for (Eigen::Index i = 0; i < F_.rows(); ++i) {
      gathered.setZero();
      for (auto k = F_.outerIndexPtr()[i]; k < F_.outerIndexPtr()[i + 1]; ++k)
        gathered += double(F_.valuePtr()[k]) * X.row(F_.innerIndexPtr()[k]);
      R.row(i) = B.row(i) - X.row(i) + rho_.row(i) * gathered;
    }
  }

  const RowBlock& diagonal() const { return D_; }

 private:
  const SparseF& F_;
  RowBlock rho_, D_;
  std::vector<std::int32_t> split_;
};

}  // namespace

namespace {

BlockSolution solve_scaled(const RadiosityProblem& p, const RowBlock& Z, double tolerance, const char* what);

}  // namespace

BlockSolution solve_block_gmres(const RadiosityProblem& p, const RowBlock& Z, double tolerance, const char* what) {
  // Each column scaled to a largest magnitude of 1 (a power of 2: exact), so that neither the norms' squares
  // overflow nor tiny columns (a channel that barely emits) lose their digits in denormals; the system is
  // linear, so the solution scales back.
  RowArray scale(Z.cols());
  for (Eigen::Index k = 0; k < Z.cols(); ++k) {
    const double largest = Z.col(k).abs().maxCoeff();
    scale(k) = largest > 0 && std::isfinite(largest) ? std::ldexp(1.0, std::ilogb(largest)) : 1.0;
  }
  BlockSolution out = solve_scaled(p, Z.rowwise() / scale, tolerance, what);
  out.X.rowwise() *= scale;
  return out;
}

namespace {

BlockSolution solve_scaled(const RadiosityProblem& p, const RowBlock& Z, double tolerance, const char* what) {
  const Eigen::Index N = static_cast<Eigen::Index>(p.size());
  const Eigen::Index K = Z.cols();
  RADWALK_CHECK_EQ(Z.rows(), N);
  RADWALK_CHECK(K % 3 == 0);
  RADWALK_CHECK(p.row_blocks.empty());
  const BlockSplitting S(p, K);
  if (!(S.diagonal() > 0).all())
    throw InputError(std::string(what) + ": a diagonal entry 1 - rho_i F_ii is not positive");
  const int m = int(std::min<Eigen::Index>(kBlockGmresRestart, std::max<Eigen::Index>(N, 1)));
  const RowArray target = tolerance * Z.abs().colwise().maxCoeff();
  BlockSolution out;
  out.X = Z / S.diagonal();
  RowBlock R(N, K), P(N, K), W(N, K);
  std::vector<RowBlock> V(std::size_t(m + 1), RowBlock(N, K));
  std::vector<Eigen::MatrixXd> H(std::size_t(K), Eigen::MatrixXd(m + 1, m));
  Eigen::MatrixXd cs(m, K), sn(m, K), g(m + 1, K);
  S.residual(Z, out.X, R);
  double best = (R.abs().colwise().maxCoeff() / target.max(1e-300)).maxCoeff();  // worst column, in targets
  int slow_cycles = 0;
  long iterations = 0;
  // Progress in the worst column's residual relative to its target's scale (solve/iteration_progress.h).
  IterationProgress progress(std::string(what) + ", GMRES iterations", tolerance, kMaxBlockGmresIterations);
  for (;;) {
    const RowArray now = R.abs().colwise().maxCoeff();
    if (!now.allFinite()) throw InputError(std::string(what) + ": the block GMRES broke down (not finite)");
    progress.update(iterations, tolerance * (now / target.max(1e-300)).maxCoeff());
    if ((now <= target).all()) break;
    if (iterations >= kMaxBlockGmresIterations)
      throw InputError(std::string(what) + " did not converge in 10,000 GMRES iterations");
    const RowArray beta = R.matrix().colwise().norm().array();
    for (Eigen::Index k = 0; k < K; ++k) V[0].col(k) = beta(k) > 0 ? (R.col(k) / beta(k)).eval() : R.col(k) * 0.0;
    g.setZero();
    g.row(0) = beta.matrix();
    for (auto& h : H) h.setZero();
    int j = 0;
    for (; j < m; ++j) {
      S.apply(V[std::size_t(j)], P, W);
      for (int i = 0; i <= j; ++i) {  // modified Gram-Schmidt, per column
        const RowArray h = (W * V[std::size_t(i)]).colwise().sum();
        for (Eigen::Index k = 0; k < K; ++k) H[std::size_t(k)](i, j) = h(k);
        W -= V[std::size_t(i)].rowwise() * h;
      }
      const RowArray norm = W.matrix().colwise().norm().array();
      bool all_small = true;
      for (Eigen::Index k = 0; k < K; ++k) {
        Eigen::MatrixXd& Hk = H[std::size_t(k)];
        Hk(j + 1, j) = norm(k);
        V[std::size_t(j + 1)].col(k) = norm(k) > 1e-300 ? (W.col(k) / norm(k)).eval() : W.col(k) * 0.0;
        for (int i = 0; i < j; ++i) {
          const double a = Hk(i, j), b = Hk(i + 1, j);
          Hk(i, j) = cs(i, k) * a + sn(i, k) * b;
          Hk(i + 1, j) = -sn(i, k) * a + cs(i, k) * b;
        }
        const double a = Hk(j, j), b = Hk(j + 1, j), h = std::hypot(a, b);
        cs(j, k) = h > 0 ? a / h : 1;
        sn(j, k) = h > 0 ? b / h : 0;
        Hk(j, j) = h;
        Hk(j + 1, j) = 0;
        g(j + 1, k) = -sn(j, k) * g(j, k);
        g(j, k) = cs(j, k) * g(j, k);
        all_small = all_small && std::abs(g(j + 1, k)) <= target(k);
      }
      ++iterations;
      if (all_small) {
        ++j;
        break;
      }
    }
    // X += M^-1 (sum_i V_i y_i) per column, H y = g.
    RowBlock update = RowBlock::Zero(N, K);
    for (Eigen::Index k = 0; k < K; ++k) {
      const Eigen::MatrixXd& Hk = H[std::size_t(k)];
      Eigen::VectorXd y = g.col(k).head(j);
      for (int i = j - 1; i >= 0; --i) {
        for (int l = i + 1; l < j; ++l) y(i) -= Hk(i, l) * y(l);
        y(i) = Hk(i, i) != 0 ? y(i) / Hk(i, i) : 0;
      }
      for (int i = 0; i < j; ++i) update.col(k) += y(i) * V[std::size_t(i)].col(k);
    }
    S.forward(update, P);
    out.X += P;
    S.residual(Z, out.X, R);
    const RowArray after = R.abs().colwise().maxCoeff();
    const double worst = (after / target.max(1e-300)).maxCoeff();
    slow_cycles = worst < 0.9 * best ? 0 : slow_cycles + 1;
    best = std::min(best, worst);
    if (slow_cycles >= 5 && !(after <= target).all())
      throw InputError(std::string(what) + ": the block GMRES stagnated (five restart cycles without reducing the "
                       "worst column's residual by 10 %): the system is singular or nearly so");
  }
  out.sweeps = iterations;
  return out;
}

}  // namespace

}  // namespace radwalk
