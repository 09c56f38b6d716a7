#pragma once
// The transpose of a square CSR matrix F, one slab of its columns at a time.
//
// For a slab of columns [begin, end) the slab holds, for each column c, the rows j with a stored F_jc in
// increasing j and their values: row c of F^T. It is built by a counting sort of F's entries whose column lies in
// the slab (each row j of F keeps a cursor at its first column not yet visited, so the slabs together read every
// entry of F once, in memory order). Rows of F and of F^T can then be merged as two sorted lists: F_ij and F_ji
// side by side for every pair, with sequential memory access, instead of a binary search in row j per entry (one
// cache miss per step at large N).
//
// Cost: O(nnz + N x slabs) time; memory besides F: 8 bytes per patch (column counts and cursors) and 8 bytes (j, F_jc) per
// entry of the largest slab. The slabs are cut so that each holds at most max(max_entries, the largest column)
// entries; a caller bounds the extra memory through max_entries (e.g. nnz / 8 for at most one byte per non-zero).
// Requires: F compressed, square, its columns increasing within each row (as every SparseF radwalk builds or
// reads); InternalError (RADWALK_CHECK) otherwise for the first two.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "formfactor/sparse_f.h"

namespace radwalk {

// An entry of F^T: F_jc in row c of F^T (j and the value side by side, so the sort writes one cache line per entry).
struct TransposedEntry {
  std::int32_t row;  // j
  float value;       // F_jc
};

// Row c of F^T, for c in the current slab: entries[k] = (j, F_jc), k < size, j increasing.
struct TransposedRow {
  const TransposedEntry* entries = nullptr;
  std::size_t size = 0;
};

class TransposeSlabs {
 public:
  TransposeSlabs(const SparseF& F, std::size_t max_entries);

  // Builds the next slab of columns; false when every column has been visited.
  bool next();
  std::size_t begin() const { return begin_; }
  std::size_t end() const { return end_; }
  // Row c of F^T, begin() <= c < end().
  TransposedRow row(std::size_t c) const {
    const std::size_t b = start_[c - begin_], e = start_[c - begin_ + 1];
    return {entries_.data() + b, e - b};
  }
  std::size_t slab_count() const { return slabs_; }

 private:
  const SparseF& F_;
  std::size_t max_entries_;
  std::vector<std::uint32_t> column_count_;  // stored entries per column of F
  std::vector<std::int32_t> cursor_;         // per row of F: its first entry in a column not yet visited
  std::vector<std::size_t> start_;           // per column of the slab: offset of its row of F^T, then the end
  std::vector<TransposedEntry> entries_;
  std::size_t begin_ = 0, end_ = 0, slabs_ = 0;
};

}  // namespace radwalk
