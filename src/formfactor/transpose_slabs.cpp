#include "formfactor/transpose_slabs.h"

#include <algorithm>

#include "core/check.h"

namespace radwalk {

TransposeSlabs::TransposeSlabs(const SparseF& F, std::size_t max_entries)
    : F_(F), max_entries_(std::max<std::size_t>(max_entries, 1)) {
  RADWALK_CHECK_EQ(F.rows(), F.cols());
  RADWALK_CHECK(F.isCompressed());
  const std::size_t N = std::size_t(F.rows()), nnz = std::size_t(F.nonZeros());
  const std::int32_t* inner = F.innerIndexPtr();
  column_count_.assign(N, 0);
  for (std::size_t k = 0; k < nnz; ++k) ++column_count_[std::size_t(inner[k])];
  cursor_.assign(F.outerIndexPtr(), F.outerIndexPtr() + N);
}

bool TransposeSlabs::next() {
  const std::size_t N = column_count_.size();
  begin_ = end_;
  if (begin_ >= N) return false;
  // The slab: columns from begin_ while their entries fit in max_entries_ (at least one column).
  std::size_t entries = column_count_[end_++];
  while (end_ < N && entries + column_count_[end_] <= max_entries_) entries += column_count_[end_++];
  start_.assign(end_ - begin_ + 1, 0);
  for (std::size_t c = begin_; c < end_; ++c) start_[c - begin_ + 1] = start_[c - begin_] + column_count_[c];
  entries_.resize(entries);
  // Counting sort: rows j in increasing order, so each column's rows come out increasing.
  std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
  const std::int32_t* outer = F_.outerIndexPtr();
  const std::int32_t* inner = F_.innerIndexPtr();
  const float* value = F_.valuePtr();
  const auto last = std::int32_t(end_);
  for (std::size_t j = 0; j < N; ++j) {
    std::int32_t k = cursor_[j];
    const std::int32_t row_end = outer[j + 1];
    for (; k < row_end && inner[k] < last; ++k) {
      entries_[fill[std::size_t(inner[k]) - begin_]++] = {std::int32_t(j), value[k]};
    }
    cursor_[j] = k;
  }
  ++slabs_;
  return true;
}

}  // namespace radwalk
