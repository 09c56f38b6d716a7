#pragma once
// The former reciprocity computations, F_ji found by a binary search in row j for every entry F_ij, kept as
// references: the tests check that the transposed slabs (formfactor/transpose_slabs.h) give the same numbers bit
// for bit, and bench_reciprocity times them side by side. Plus a brute-force reference of the diagnostics'
// reciprocity error straight from its definition (dense lookups, O(N^2): small matrices only).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "core/parallel.h"
#include "formfactor/reciprocity.h"
#include "formfactor/sparse_f.h"

namespace radwalk::test {

// reciprocity_error[i] = max_j |A_i F_ij - A_j F_ji| / max(A_i F_ij, A_j F_ji) over j with F_ij or F_ji stored,
// 1 where one side of a pair is stored and positive and the other absent; by dense lookups of the definition.
inline std::vector<double> brute_force_reciprocity_error(const SparseF& F, const std::vector<double>& area) {
  const Eigen::Index N = F.rows();
  std::vector<std::vector<bool>> stored(std::size_t(N), std::vector<bool>(std::size_t(N), false));
  std::vector<std::vector<float>> v(std::size_t(N), std::vector<float>(std::size_t(N), 0.0f));
  for (Eigen::Index i = 0; i < N; ++i)
    for (SparseF::InnerIterator it(F, i); it; ++it) {
      stored[std::size_t(i)][std::size_t(it.index())] = true;
      v[std::size_t(i)][std::size_t(it.index())] = it.value();
    }
  std::vector<double> err(std::size_t(N), 0.0);
  for (std::size_t i = 0; i < std::size_t(N); ++i)
    for (std::size_t j = 0; j < std::size_t(N); ++j) {
      if (!stored[i][j] && !stored[j][i]) continue;
      const double gij = stored[i][j] ? area[i] * v[i][j] : 0.0, gji = stored[j][i] ? area[j] * v[j][i] : 0.0;
      if (stored[i][j] != stored[j][i]) {
        if ((stored[i][j] ? gij : gji) > 0) err[i] = std::max(err[i], 1.0);
        continue;
      }
      const double m = std::max(gij, gji);
      if (m > 0) err[i] = std::max(err[i], std::abs(gij - gji) / m);
    }
  return err;
}

// The former reciprocity error of diagnose_form_factors (binary search in row j per entry; F compressed).
inline std::vector<double> binary_search_reciprocity_error(const SparseF& F, const std::vector<double>& area) {
  const std::size_t N = std::size_t(F.rows());
  std::vector<double> reciprocity_error(N, 0.0);
  std::vector<std::atomic<std::uint8_t>> one_sided(N);
  const std::int32_t* outer = F.outerIndexPtr();
  const std::int32_t* inner = F.innerIndexPtr();
  const float* value = F.valuePtr();
  parallel_for(N, [&](std::size_t i) {
    // Reciprocity over the j of row i: F_ji by binary search in row j (0 when absent).
    double worst = 0;
    for (std::int32_t k = outer[i]; k < outer[i + 1]; ++k) {
      const std::int32_t j = inner[k];
      const std::int32_t* row_j = inner + outer[j];
      const std::int32_t* end_j = inner + outer[j + 1];
      const std::int32_t* at = std::lower_bound(row_j, end_j, std::int32_t(i));
      const bool found = at != end_j && *at == std::int32_t(i);
      const double gij = area[i] * value[k], gji = found ? area[std::size_t(j)] * value[at - inner] : 0.0;
      if (!found && gij > 0) one_sided[std::size_t(j)].store(1, std::memory_order_relaxed);
      const double m = std::max(gij, gji);
      if (m > 0) worst = std::max(worst, std::abs(gij - gji) / m);
    }
    reciprocity_error[i] = worst;
  });
  for (std::size_t i = 0; i < N; ++i)
    if (one_sided[i].load(std::memory_order_relaxed)) reciprocity_error[i] = std::max(reciprocity_error[i], 1.0);
  return reciprocity_error;
}

// The former enforce_reciprocity (binary search in row j per entry).
inline ReciprocityChange binary_search_enforce_reciprocity(SparseF& F, const std::vector<double>& area) {
  const std::size_t N = std::size_t(F.rows());
  if (!F.isCompressed()) F.makeCompressed();
  const std::int32_t* outer = F.outerIndexPtr();
  const std::int32_t* inner = F.innerIndexPtr();
  const float* value = F.valuePtr();
  // F_ji of row j (columns increase), or nullptr when absent.
  const auto entry = [&](std::int32_t j, std::int32_t i) -> const float* {
    const std::int32_t* end = inner + outer[j + 1];
    const std::int32_t* at = std::lower_bound(inner + outer[j], end, i);
    return at != end && *at == i ? value + (at - inner) : nullptr;
  };

  // Step 1: the one-sided entries, F_ji present and F_ij absent, as extra columns j of row i (each row's in
  // increasing j): S = (G + G^T) / 2, G = diag(A) F, has the pattern of F and F^T, and these are what F^T adds.
  // Memory: 1 byte per non-zero of F and 4 per extra entry, not the transposes of G (no copy of F).
  const std::size_t nnz = std::size_t(F.nonZeros());
  std::vector<std::uint8_t> one_sided(nnz);
  parallel_for(N, [&](std::size_t j) {
    for (std::int32_t k = outer[j]; k < outer[j + 1]; ++k)
      one_sided[std::size_t(k)] = entry(inner[k], std::int32_t(j)) == nullptr;
  });
  std::vector<std::size_t> extra_start(N + 1, 0);
  for (std::size_t j = 0; j < N; ++j)
    for (std::int32_t k = outer[j]; k < outer[j + 1]; ++k) extra_start[std::size_t(inner[k]) + 1] += one_sided[std::size_t(k)];
  for (std::size_t i = 0; i < N; ++i) extra_start[i + 1] += extra_start[i];
  const std::size_t extras = extra_start[N];
  if (nnz + extras > std::size_t(std::numeric_limits<std::int32_t>::max()))
    throw std::length_error("more than 2^31-1 non-zeros");
  std::vector<std::int32_t> extra_col(extras);
  {
    std::vector<std::size_t> cursor(extra_start.begin(), extra_start.end() - 1);
    for (std::size_t j = 0; j < N; ++j)
      for (std::int32_t k = outer[j]; k < outer[j + 1]; ++k)
        if (one_sided[std::size_t(k)]) extra_col[cursor[std::size_t(inner[k])]++] = std::int32_t(j);
  }
  one_sided = {};

  // Step 2, row by row: S_ij = (A_i F_ij + A_j F_ji) / 2 (an absent side counts 0), F'_ij = S_ij / A_i, the row
  // rescaled when it sums above 1, the change measured entry by entry against F, stored as float.
  SparseF out(static_cast<Eigen::Index>(N), static_cast<Eigen::Index>(N));
  out.resizeNonZeros(Eigen::Index(nnz + extras));
  std::int32_t* out_outer = out.outerIndexPtr();
  std::int32_t* out_inner = out.innerIndexPtr();
  float* out_value = out.valuePtr();
  ReciprocityChange change;
  double change_sum = 0;
  std::size_t entries = 0, at = 0;
  std::vector<double> row;          // F'_ij of the row, in column order
  std::vector<double> before;       // F_ij (0 where absent)
  out_outer[0] = 0;
  for (std::size_t i = 0; i < N; ++i) {
    row.clear();
    before.clear();
    const std::size_t row_start = at;
    std::int32_t k = outer[i];
    std::size_t x = extra_start[i];
    while (k < outer[i + 1] || x < extra_start[i + 1]) {
      std::int32_t j;
      double s;
      if (x == extra_start[i + 1] || (k < outer[i + 1] && inner[k] < extra_col[x])) {
        j = inner[k];
        const double gij = area[i] * double(value[k]);
        const float* fji = entry(j, std::int32_t(i));
        s = fji ? gij + area[std::size_t(j)] * double(*fji) : gij;
        before.push_back(double(value[k]));
        ++k;
      } else {
        j = extra_col[x++];
        s = area[std::size_t(j)] * double(*entry(j, std::int32_t(i)));
        before.push_back(0.0);
      }
      out_inner[at++] = j;
      row.push_back(0.5 * s);
    }
    double sum = 0;
    for (double& v : row) sum += (v /= area[i]);
    if (sum > 1.0) {
      for (double& v : row) v /= sum;
      ++change.rows_rescaled;
      change.max_row_excess = std::max(change.max_row_excess, sum - 1.0);
    }
    for (std::size_t q = 0; q < row.size(); ++q) {
      const double m = std::max(before[q], row[q]);
      const double rel = m > 0 ? std::abs(row[q] - before[q]) / m : 0.0;
      change.max_relative_change = std::max(change.max_relative_change, rel);
      change_sum += rel;
      ++entries;
      out_value[row_start + q] = static_cast<float>(row[q]);
    }
    out_outer[i + 1] = std::int32_t(at);
  }
  change.mean_relative_change = entries ? change_sum / double(entries) : 0.0;
  F = std::move(out);
  return change;
}

}  // namespace radwalk::test
