#include "formfactor/closure.h"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <string>

#include "core/check.h"
#include "core/error.h"

namespace radwalk {
namespace {

using SparseD = Eigen::SparseMatrix<double, Eigen::RowMajor, std::int32_t>;

std::string patch_text(std::size_t i) { return "patch " + std::to_string(i) + " (0-based)"; }

}  // namespace

ClosureChange enforce_closure(SparseF& F, const std::vector<double>& area, const std::vector<std::uint32_t>& rays) {
  const std::size_t N = std::size_t(F.rows());
  RADWALK_CHECK_EQ(F.cols(), F.rows());
  RADWALK_CHECK_EQ(area.size(), N);
  if (!rays.empty()) RADWALK_CHECK_EQ(rays.size(), N);
  for (std::size_t i = 0; i < N; ++i)
    if (!(std::isfinite(area[i]) && area[i] > 0))
      throw InputError("closure: " + patch_text(i) + " has area " + std::to_string(area[i]) + ", not > 0");
  if (!F.isCompressed()) F.makeCompressed();
  const auto n_of = [&](std::size_t i) { return rays.empty() ? 1.0 : std::max(1.0, double(rays[i])); };

  // The symmetrised exchange areas m = (G + G^T) / 2, G = diag(A) F, on the union of the two patterns.
  SparseD G = F.cast<double>();
  for (Eigen::Index i = 0; i < G.outerSize(); ++i)
    for (SparseD::InnerIterator it(G, i); it; ++it) it.valueRef() *= area[std::size_t(i)];
  const SparseD Gt = G.transpose();
  SparseD M = 0.5 * (G + Gt);
  M.makeCompressed();
  const std::int32_t* outer = M.outerIndexPtr();
  const std::int32_t* inner = M.innerIndexPtr();
  const double* m = M.valuePtr();
  const std::size_t nnz = std::size_t(M.nonZeros());

  ClosureChange change;
  std::vector<double> defect_before(N, 0.0);
  for (std::size_t i = 0; i < N; ++i) {
    double row = 0;
    for (SparseF::InnerIterator it(F, Eigen::Index(i)); it; ++it) row += double(it.value());
    change.max_row_defect_before = std::max(change.max_row_defect_before, std::abs(1 - row));
    if (outer[i + 1] == outer[i])
      throw InputError("closure: " + patch_text(i) + " sees no other patch and no patch sees it (its row and "
                       "column of F are empty): no adjustment can make its row sum to 1; trace more rays or "
                       "remove the patch");
  }

  // s_p per stored entry (the variance factor), and which entries are free (not clipped to 0).
  std::vector<double> s(nnz);
  std::vector<char> free_entry(nnz, 1);
  for (std::size_t i = 0; i < N; ++i)
    for (std::int32_t k = outer[i]; k < outer[i + 1]; ++k) {
      const std::size_t j = std::size_t(inner[k]);
      s[std::size_t(k)] = j == i ? area[i] / n_of(i) : 0.25 * (area[i] / n_of(i) + area[j] / n_of(j));
      if (!(m[k] > 0)) free_entry[std::size_t(k)] = 0;  // a stored zero stays zero
    }

  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(Eigen::Index(N));
  for (int round = 1;; ++round) {
    // The Lagrange system L lambda = d over the free entries.
    std::vector<Eigen::Triplet<double, std::int32_t>> triplets;
    triplets.reserve(nnz + N);
    Eigen::VectorXd d = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(N));
    for (std::size_t i = 0; i < N; ++i) {
      double diagonal = 0, rest = area[i];
      for (std::int32_t k = outer[i]; k < outer[i + 1]; ++k) {
        if (!free_entry[std::size_t(k)]) continue;
        const double w = m[k] * s[std::size_t(k)];
        diagonal += w;
        rest -= m[k];
        if (std::size_t(inner[k]) != i) triplets.emplace_back(std::int32_t(i), inner[k], w);
      }
      if (!(diagonal > 0))
        throw InputError("closure: every entry of " + patch_text(i) + "'s row would have to become negative to "
                         "close it: the form factors are too noisy for a closed adjustment (trace more rays)");
      triplets.emplace_back(std::int32_t(i), std::int32_t(i), diagonal);
      d(Eigen::Index(i)) = rest;
    }
    Eigen::SparseMatrix<double> L(static_cast<Eigen::Index>(N), static_cast<Eigen::Index>(N));
    L.setFromTriplets(triplets.begin(), triplets.end());
    Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg;
    cg.setTolerance(1e-13);
    cg.setMaxIterations(std::max<Eigen::Index>(1000, 10 * Eigen::Index(N)));
    cg.compute(L);
    lambda = cg.solveWithGuess(d, lambda);
    change.rounds = round;
    change.cg_iterations = long(cg.iterations());
    change.cg_error = cg.error();
    // Entries that would become negative leave the free set; none: done.
    std::size_t clipped_now = 0;
    for (std::size_t i = 0; i < N; ++i)
      for (std::int32_t k = outer[i]; k < outer[i + 1]; ++k) {
        if (!free_entry[std::size_t(k)]) continue;
        const std::size_t j = std::size_t(inner[k]);
        const double factor = 1 + s[std::size_t(k)] * (j == i ? lambda(Eigen::Index(i))
                                                               : lambda(Eigen::Index(i)) + lambda(Eigen::Index(j)));
        if (factor < 0) free_entry[std::size_t(k)] = 0, ++clipped_now;
      }
    if (clipped_now == 0) break;
    change.clipped += clipped_now;
    if (round == kClosureActiveSetRounds)
      throw InputError("closure: the non-negative adjustment did not settle in " +
                       std::to_string(kClosureActiveSetRounds) + " rounds (" + std::to_string(change.clipped) +
                       " entries clipped to 0): the form factors are too noisy for a closed adjustment (trace more "
                       "rays)");
  }
  if (!(change.cg_error <= 1e-8))
    throw InputError("closure: the Lagrange system was not solved (relative residual " +
                     std::to_string(change.cg_error) + " after " + std::to_string(change.cg_iterations) +
                     " conjugate-gradient iterations): its graph may be bipartite with unequal areas on the two "
                     "sides, which no symmetric closed F allows");

  // F' = X' / A on M's pattern (clipped entries 0), and the change per row.
  SparseF out = M.cast<float>();
  out.makeCompressed();
  float* value = out.valuePtr();
  change.row_max_change.assign(N, 0.0);
  change.row_rms_change.assign(N, 0.0);
  double total_square = 0;
  for (std::size_t i = 0; i < N; ++i) {
    SparseF::InnerIterator before(F, Eigen::Index(i));
    double square = 0, row = 0;
    for (std::int32_t k = outer[i]; k < outer[i + 1]; ++k) {
      const std::size_t j = std::size_t(inner[k]);
      double x = 0;
      if (free_entry[std::size_t(k)])
        x = m[k] * (1 + s[std::size_t(k)] * (j == i ? lambda(Eigen::Index(i))
                                                     : lambda(Eigen::Index(i)) + lambda(Eigen::Index(j))));
      value[k] = float(x / area[i]);
      row += double(value[k]);
      while (before && std::size_t(before.col()) < j) ++before;
      const double old = before && std::size_t(before.col()) == j ? double(before.value()) : 0.0;
      const double delta = double(value[k]) - old;
      change.row_max_change[i] = std::max(change.row_max_change[i], std::abs(delta));
      square += delta * delta;
    }
    const std::int32_t entries = outer[i + 1] - outer[i];
    change.row_rms_change[i] = std::sqrt(square / double(entries));
    total_square += square;
    change.max_change = std::max(change.max_change, change.row_max_change[i]);
    change.max_row_defect_after = std::max(change.max_row_defect_after, std::abs(1 - row));
  }
  change.rms_change = nnz > 0 ? std::sqrt(total_square / double(nnz)) : 0.0;
  // Reciprocity of the stored F': the pattern is symmetric, so row i of F'^T has the columns of row i of F'.
  {
    const SparseF Ot = out.transpose();
    for (std::size_t i = 0; i < N; ++i) {
      SparseF::InnerIterator a(out, Eigen::Index(i)), b(Ot, Eigen::Index(i));
      for (; a && b; ++a, ++b) {
        RADWALK_CHECK_EQ(a.col(), b.col());
        const double x = area[i] * double(a.value()), y = area[std::size_t(b.col())] * double(b.value());
        const double larger = std::max(x, y);
        if (larger > 0) change.max_reciprocity_defect_after = std::max(change.max_reciprocity_defect_after,
                                                                       std::abs(x - y) / larger);
      }
    }
  }
  out.prune(0.0f);
  F = std::move(out);
  return change;
}

}  // namespace radwalk
