#include "solve/spectral_radius.h"

#include <algorithm>
#include <limits>
#include <vector>

#include "core/parallel.h"
#include "core/progress.h"
#include "solve/distributed_sweeps.h"

namespace radwalk {
namespace {

// Over MPI with a row-distributed F (problem.h) each rank computes its own rows of a product, then the ranks
// exchange them (distributed_sweeps.h): every rank has the whole vector, with the bits one process computes.
// Collective then.
void share_rows(Eigen::VectorXd& v, const RowBlocks& blocks) {
  if (holds_own_rows_only(blocks)) exchange_rows(v, blocks);
}

// s_i = sum_j F_ij.
Eigen::VectorXd row_sums(const SparseF& F, const RowBlocks& blocks) {
  Eigen::VectorXd s(F.rows());
  parallel_for(static_cast<std::size_t>(F.rows()), [&](std::size_t i) {
    double t = 0;
    for (SparseF::InnerIterator it(F, static_cast<Eigen::Index>(i)); it; ++it) t += it.value();
    s(static_cast<Eigen::Index>(i)) = t;
  }, 256);
  share_rows(s, blocks);
  return s;
}

// y = diag(rho) F x.
void apply_H(const SparseF& F, const RowBlocks& blocks, const Eigen::VectorXd& rho, const Eigen::VectorXd& x,
             Eigen::VectorXd& y) {
  parallel_for(static_cast<std::size_t>(F.rows()), [&](std::size_t i) {
    const auto r = static_cast<Eigen::Index>(i);
    double t = 0;
    for (SparseF::InnerIterator it(F, r); it; ++it) t += double(it.value()) * x(it.col());
    y(r) = rho(r) * t;
  }, 256);
  share_rows(y, blocks);
}

struct ChannelRadius {
  double lower = 0, upper = 0, estimate = 0;
  int products = 0;
};

ChannelRadius power_iteration(const SparseF& F, const RowBlocks& blocks, const Eigen::VectorXd& rho, double bound,
                              int max_products, double rel_tol, Progress& progress) {
  const Eigen::Index n = F.rows();
  ChannelRadius r;
  r.upper = bound;
  Eigen::VectorXd x = Eigen::VectorXd::Constant(n, 1.0 / double(n)), y(n), y_prev(n);
  double s_prev = 0;  // x_k = (x_{k-1} + y_{k-1}) / s_prev
  for (int k = 0; k < max_products; ++k) {
    apply_H(F, blocks, rho, x, y);
    ++r.products;
    progress.advance(1);
    // Upper bound from x > 0; lower bound from v = y_{k-1} with H v = s_prev * y - y_prev.
    double upper = 0;
    for (Eigen::Index i = 0; i < n; ++i) upper = std::max(upper, y(i) / x(i));
    r.upper = std::min(r.upper, upper);
    if (k > 0) {
      double lower = std::numeric_limits<double>::infinity();
      bool any = false;
      for (Eigen::Index i = 0; i < n; ++i)
        if (y_prev(i) > 0) {
          lower = std::min(lower, (s_prev * y(i) - y_prev(i)) / y_prev(i));
          any = true;
        }
      if (any) r.lower = std::max(r.lower, lower);
    }
    const double sy = y.sum();
    r.estimate = std::clamp(sy / x.sum(), r.lower, r.upper);
    if (sy == 0) {  // H x = 0 for x > 0: H = 0
      r.lower = r.upper = r.estimate = 0;
      break;
    }
    if (r.upper - r.lower <= rel_tol * r.upper) break;
    // Next iterate of I + H, normalised to sum 1.
    s_prev = x.sum() + sy;
    x = (x + y) / s_prev;
    y_prev = y;
  }
  return r;
}

}  // namespace

SpectralRadius spectral_radius_bound(const RadiosityProblem& p) {
  SpectralRadius r;
  if (p.size() == 0) return r;
  const Eigen::VectorXd sums = row_sums(p.F, p.row_blocks);
  r.max_row_sum = sums.maxCoeff();
  r.max_rho = p.rho.maxCoeff();
  for (int c = 0; c < 3; ++c) {
    const double b = (p.rho.col(c).matrix().cwiseProduct(sums)).maxCoeff();
    if (b > r.bound || c == 0) {
      r.bound = b;
      r.channel = c;
    }
  }
  r.upper = r.estimate = r.bound;
  return r;
}

SpectralRadius estimate_spectral_radius(const RadiosityProblem& p, int max_products, double rel_tol) {
  SpectralRadius r = spectral_radius_bound(p);
  if (p.size() == 0 || r.bound == 0) return r;
  const Eigen::VectorXd sums = row_sums(p.F, p.row_blocks);
  r.estimate = r.upper = r.lower = -1;
  Progress progress("spectral radius (power iteration)", 3 * static_cast<std::size_t>(std::max(max_products, 0)));
  for (int c = 0; c < 3; ++c) {
    // A channel whose rho equals an earlier one has the same radius.
    bool repeated = false;
    for (int d = 0; d < c; ++d) repeated = repeated || (p.rho.col(c) == p.rho.col(d)).all();
    if (repeated) {
      progress.advance(static_cast<std::size_t>(std::max(max_products, 0)));
      continue;
    }
    const Eigen::VectorXd rho = p.rho.col(c).matrix();
    const double bound = rho.cwiseProduct(sums).maxCoeff();
    const ChannelRadius cr = power_iteration(p.F, p.row_blocks, rho, bound, max_products, rel_tol, progress);
    progress.advance(static_cast<std::size_t>(std::max(max_products - cr.products, 0)));  // stopped early
    r.products += cr.products;
    if (cr.estimate > r.estimate) {
      r.estimate = cr.estimate;
      r.channel = c;
    }
    r.upper = std::max(r.upper, cr.upper);
    r.lower = std::max(r.lower, cr.lower);
  }
  return r;
}

}  // namespace radwalk
