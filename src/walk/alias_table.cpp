#include "walk/alias_table.h"

#include <cmath>
#include <string>

#include "core/check.h"
#include "core/error.h"

namespace radwalk {

RowAliasTables::RowAliasTables(const SparseF& F) {
  RADWALK_CHECK_EQ(F.rows(), F.cols());  // F is square (the reader and the estimator guarantee it)
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
