#include "walk/alias_table.h"

#include <cmath>
#include <string>

#include "core/error.h"

namespace radwalk {

void build_alias_buckets(const double* q, const std::int32_t* outcome, std::size_t n, AliasBucket* buckets) {
  // Scaled probabilities n q_b; "small" buckets (< 1) borrow from "large" ones (>= 1).
  std::vector<double> scaled(n);
  std::vector<std::size_t> small, large;
  small.reserve(n);
  large.reserve(n);
  for (std::size_t b = 0; b < n; ++b) {
    scaled[b] = q[b] * static_cast<double>(n);
    (scaled[b] < 1.0 ? small : large).push_back(b);
  }
  // Pair each small bucket with a large donor; the donor's remainder goes back to the matching list.
  while (!small.empty() && !large.empty()) {
    const std::size_t s = small.back(), l = large.back();
    small.pop_back();
    large.pop_back();
    buckets[s] = {scaled[s], outcome[s], outcome[l]};
    scaled[l] = (scaled[l] + scaled[s]) - 1.0;
    (scaled[l] < 1.0 ? small : large).push_back(l);
  }
  // Leftovers are full buckets up to rounding.
  for (std::size_t b : large) buckets[b] = {1.0, outcome[b], outcome[b]};
  for (std::size_t b : small) buckets[b] = {1.0, outcome[b], outcome[b]};
}

AliasTable::AliasTable(const std::vector<double>& weights) {
  double total = 0;
  for (double w : weights) {
    if (!(w >= 0) || !std::isfinite(w)) throw InputError("alias table: weight " + std::to_string(w) + " is not a finite non-negative number");
    total += w;
  }
  if (!(total > 0)) throw InputError("alias table: all weights are zero");
  const std::size_t n = weights.size();
  pdf_.resize(n);
  std::vector<std::int32_t> outcome(n);
  for (std::size_t i = 0; i < n; ++i) {
    pdf_[i] = weights[i] / total;
    outcome[i] = static_cast<std::int32_t>(i);
  }
  buckets_.resize(n);
  build_alias_buckets(pdf_.data(), outcome.data(), n, buckets_.data());
}

RowAliasTables::RowAliasTables(const SparseF& F) {
  if (F.rows() != F.cols())
    throw InputError("row alias tables: F is " + std::to_string(F.rows()) + " x " + std::to_string(F.cols()) +
                     ", not square");
  const auto N = static_cast<std::size_t>(F.rows());
  row_sum_.assign(N, 0.0);
  begin_.assign(N + 1, 0);
  // Row sums, and the bucket count of each row: its stored entries plus one escape bucket where s_k < 1.
  for (std::size_t k = 0; k < N; ++k) {
    double s = 0;
    std::size_t entries = 0;
    for (SparseF::InnerIterator it(F, static_cast<Eigen::Index>(k)); it; ++it) {
      const double f = it.value();
      if (!(f >= 0) || !std::isfinite(f))
        throw InputError("row alias tables: F(" + std::to_string(k) + ", " + std::to_string(it.col()) + ") = " +
                         std::to_string(f) + " is not a finite non-negative number");
      s += f;
      ++entries;
    }
    row_sum_[k] = s;
    begin_[k + 1] = begin_[k] + entries + (s < 1.0 ? 1 : 0);
  }
  buckets_.resize(begin_[N]);
  // One Vose table per row over (F_kj / n_k ..., escape).
  std::vector<double> q;
  std::vector<std::int32_t> outcome;
  for (std::size_t k = 0; k < N; ++k) {
    q.clear();
    outcome.clear();
    const double scale = row_scale(k);
    for (SparseF::InnerIterator it(F, static_cast<Eigen::Index>(k)); it; ++it) {
      q.push_back(double(it.value()) / scale);
      outcome.push_back(static_cast<std::int32_t>(it.col()));
    }
    if (row_sum_[k] < 1.0) {
      q.push_back(1.0 - row_sum_[k]);
      outcome.push_back(kEscaped);
    }
    build_alias_buckets(q.data(), outcome.data(), q.size(), buckets_.data() + begin_[k]);
  }
}

double RowAliasTables::pdf(std::size_t k, PatchIndex j) const {
  const std::size_t n = begin_[k + 1] - begin_[k];
  double p = 0;
  for (std::size_t b = begin_[k]; b < begin_[k + 1]; ++b) {
    if (buckets_[b].primary == j) p += buckets_[b].threshold;
    if (buckets_[b].alias == j) p += 1.0 - buckets_[b].threshold;
  }
  return p / static_cast<double>(n);
}

std::size_t RowAliasTables::memory_bytes() const {
  return buckets_.size() * sizeof(AliasBucket) + begin_.size() * sizeof(std::size_t) +
         row_sum_.size() * sizeof(double);
}

}  // namespace radwalk
