#include "solve/residual.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "solve/distributed_sweeps.h"

namespace radwalk {

PatchRgb multiply_F(const SparseF& F, const PatchRgb& B) {
  PatchRgb FB(F.rows(), 3);
  parallel_for(static_cast<std::size_t>(F.rows()), [&](std::size_t i) {
    double s0 = 0, s1 = 0, s2 = 0;
    for (SparseF::InnerIterator it(F, static_cast<Eigen::Index>(i)); it; ++it) {
      const double f = it.value();
      const auto j = it.col();
      s0 += f * B(j, 0);
      s1 += f * B(j, 1);
      s2 += f * B(j, 2);
    }
    FB(i, 0) = s0;
    FB(i, 1) = s1;
    FB(i, 2) = s2;
  }, 256);
  return FB;
}

PatchRgb residual(const RadiosityProblem& p, const PatchRgb& B) {
  PatchRgb r = p.E + p.rho * multiply_F(p.F, B) - B;
  // Row-distributed F: each rank's own rows are right; the exchange gives every rank every row.
  if (holds_own_rows_only(p.row_blocks)) exchange_rows(r, p.row_blocks);
  return r;
}

Rgb residual_scale(const PatchRgb& E) {
  Rgb s = Rgb::Zero();
  if (E.rows() > 0) s = E.abs().colwise().maxCoeff().transpose();
  const double largest = s.maxCoeff();
  for (int c = 0; c < 3; ++c)
    if (!(s(c) > 0)) s(c) = largest > 0 ? largest : 1.0;
  return s;
}

double relative_norm(const PatchRgb& r, const Rgb& scale) {
  if (r.rows() == 0) return 0;
  double worst = 0;
  for (int c = 0; c < 3; ++c) {
    const double v = r.col(c).abs().maxCoeff() / scale(c);
    if (std::isnan(v)) return v;
    worst = std::max(worst, v);
  }
  return worst;
}

PatchRgb system_diagonal(const RadiosityProblem& p) {
  PatchRgb D = PatchRgb::Ones(Eigen::Index(p.size()), 3);
  for (Eigen::Index i = 0; i < D.rows(); ++i)
    for (SparseF::InnerIterator it(p.F, i); it; ++it)
      if (it.col() == i) D.row(i) -= p.rho.row(i) * double(it.value());
  if (holds_own_rows_only(p.row_blocks)) exchange_rows(D, p.row_blocks);  // F_ii from the rank holding row i
  return D;
}

double relative_residual(const RadiosityProblem& p, const PatchRgb& B) {
  if (!holds_own_rows_only(p.row_blocks)) return relative_norm(residual(p, B), residual_scale(p.E));
  // Row-distributed F: the norm of the own rows, then the largest over the ranks (a max, so the same number).
  const distributed::Range mine = own_rows(p.row_blocks, p.size());
  const auto first = Eigen::Index(mine.begin), rows = Eigen::Index(mine.size());
  const PatchRgb r = p.E.middleRows(first, rows) +
                     p.rho.middleRows(first, rows) * multiply_F(p.F, B).middleRows(first, rows) -
                     B.middleRows(first, rows);
  return distributed::max_over_ranks(relative_norm(r, residual_scale(p.E)));
}

}  // namespace radwalk
