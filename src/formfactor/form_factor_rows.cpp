#include "formfactor/form_factor_rows.h"

#include <cstring>
#include <limits>

#include "core/error.h"

namespace radwalk {
namespace {

long g_gathers = 0;  // whole_row_gathers()

// Row i's start and length in F's arrays (compressed or not).
std::size_t row_start(const SparseF& F, std::size_t i) { return static_cast<std::size_t>(F.outerIndexPtr()[i]); }
std::size_t row_length(const SparseF& F, std::size_t i) {
  return static_cast<std::size_t>(F.isCompressed() ? F.outerIndexPtr()[i + 1] - F.outerIndexPtr()[i]
                                                   : F.innerNonZeroPtr()[i]);
}

// CSR outer index from row lengths: outer[i + 1] = outer[i] + length[i]. InputError past the 32-bit range.
void prefix_sums(const std::vector<std::int32_t>& length, std::int32_t* outer) {
  std::int64_t at = 0;
  outer[0] = 0;
  for (std::size_t i = 0; i < length.size(); ++i) {
    at += length[i];
    if (at > std::numeric_limits<std::int32_t>::max())
      throw InputError("form factors: the rows of all ranks hold more than 2^31-1 non-zeros (the 32-bit index range)");
    outer[i + 1] = static_cast<std::int32_t>(at);
  }
}

// The lengths of this rank's rows (the other entries 0).
std::vector<std::int32_t> own_lengths(const SparseF& F, distributed::Range mine) {
  std::vector<std::int32_t> length(static_cast<std::size_t>(F.rows()), 0);
  for (std::size_t i = mine.begin; i < mine.end; ++i) length[i] = static_cast<std::int32_t>(row_length(F, i));
  return length;
}

}  // namespace

distributed::Range own_rows(const RowBlocks& blocks, std::size_t n) {
  return holds_own_rows_only(blocks) ? blocks[static_cast<std::size_t>(distributed::rank())]
                                     : distributed::Range{0, n};
}

RowBlocks nonzero_row_blocks(const std::int32_t* outer, std::size_t n) {
  std::vector<double> weights(n);
  for (std::size_t i = 0; i < n; ++i) weights[i] = 1.0 + double(outer[i + 1] - outer[i]);
  return distributed::weighted_blocks(weights);
}

SparseF keep_rows(const SparseF& F, distributed::Range keep) {
  const auto n = static_cast<std::size_t>(F.rows());
  std::vector<std::int32_t> length(n, 0);
  for (std::size_t i = keep.begin; i < keep.end; ++i) length[i] = static_cast<std::int32_t>(row_length(F, i));
  SparseF out(F.rows(), F.cols());
  prefix_sums(length, out.outerIndexPtr());
  out.resizeNonZeros(out.outerIndexPtr()[n]);
  for (std::size_t i = keep.begin; i < keep.end; ++i) {
    const std::size_t from = row_start(F, i), to = row_start(out, i), m = row_length(F, i);
    std::memcpy(out.innerIndexPtr() + to, F.innerIndexPtr() + from, m * sizeof(std::int32_t));
    std::memcpy(out.valuePtr() + to, F.valuePtr() + from, m * sizeof(float));
  }
  return out;
}

void gather_whole_rows(SparseF& F, RowBlocks& blocks) {
  if (!holds_own_rows_only(blocks)) {
    blocks.clear();
    return;
  }
  ++g_gathers;
  F.makeCompressed();
  const distributed::Range mine = blocks[static_cast<std::size_t>(distributed::rank())];
  std::vector<std::int32_t> length = own_lengths(F, mine);
  distributed::share_blocks(length, blocks);
  // Straight from F's arrays (no copy into a vector first), then back into them: the ranks' rows in rank order
  // are the rows in order (the blocks are contiguous and increasing).
  const std::size_t first = row_start(F, mine.begin), local = row_start(F, mine.end) - first;
  const std::vector<char> cols =
      distributed::allgather_concat_bytes(F.innerIndexPtr() + first, local, sizeof(std::int32_t));
  const std::vector<char> values = distributed::allgather_concat_bytes(F.valuePtr() + first, local, sizeof(float));
  prefix_sums(length, F.outerIndexPtr());
  const std::size_t total = static_cast<std::size_t>(F.outerIndexPtr()[F.rows()]);
  RADWALK_CHECK_EQ(total * sizeof(std::int32_t), cols.size());  // every rank sent its rows' entries
  F.resizeNonZeros(Eigen::Index(total));
  if (total > 0) {
    std::memcpy(F.innerIndexPtr(), cols.data(), cols.size());
    std::memcpy(F.valuePtr(), values.data(), values.size());
  }
  blocks.clear();
}

long whole_row_gathers() { return g_gathers; }

const SparseF& gather_rows_to_root(const SparseF& F, const RowBlocks& blocks, SparseF& gathered) {
  if (!holds_own_rows_only(blocks)) return F;
  const auto n = static_cast<std::size_t>(F.rows());
  const distributed::Range mine = blocks[static_cast<std::size_t>(distributed::rank())];
  const std::size_t first = row_start(F, mine.begin);
  RADWALK_CHECK(F.isCompressed());  // own rows contiguous in F's arrays
  const std::size_t local = row_start(F, mine.end) - first;
  if (!distributed::is_root()) {
    const std::vector<std::int32_t> length = own_lengths(F, mine);
    distributed::send_to_root(length.data() + mine.begin, mine.size() * sizeof(std::int32_t));
    distributed::send_to_root(F.innerIndexPtr() + first, local * sizeof(std::int32_t));
    distributed::send_to_root(F.valuePtr() + first, local * sizeof(float));
    gathered = SparseF(F.rows(), F.cols());
    return gathered;
  }
  // Rank 0 holds the first block: its rows, then every other rank's in rank order, each received into place.
  std::vector<std::int32_t> length = own_lengths(F, mine);
  for (int r = 1; r < distributed::size(); ++r) {
    const distributed::Range theirs = blocks[static_cast<std::size_t>(r)];
    distributed::receive_into(r, length.data() + theirs.begin, theirs.size() * sizeof(std::int32_t));
  }
  gathered = SparseF(F.rows(), F.cols());
  prefix_sums(length, gathered.outerIndexPtr());
  gathered.resizeNonZeros(gathered.outerIndexPtr()[n]);
  std::memcpy(gathered.innerIndexPtr(), F.innerIndexPtr() + first, local * sizeof(std::int32_t));
  std::memcpy(gathered.valuePtr(), F.valuePtr() + first, local * sizeof(float));
  for (int r = 1; r < distributed::size(); ++r) {
    const distributed::Range theirs = blocks[static_cast<std::size_t>(r)];
    const std::size_t at = row_start(gathered, theirs.begin), count = row_start(gathered, theirs.end) - at;
    distributed::receive_into(r, gathered.innerIndexPtr() + at, count * sizeof(std::int32_t));
    distributed::receive_into(r, gathered.valuePtr() + at, count * sizeof(float));
  }
  return gathered;
}

std::uint64_t total_nonzeros(const SparseF& F, const RowBlocks& blocks) {
  if (!holds_own_rows_only(blocks)) return static_cast<std::uint64_t>(F.nonZeros());
  std::uint64_t total = 0;
  for (std::uint64_t k : nonzeros_by_rank(F)) total += k;
  return total;
}

std::vector<std::uint64_t> nonzeros_by_rank(const SparseF& F) {
  return distributed::allgather_concat(std::vector<std::uint64_t>{static_cast<std::uint64_t>(F.nonZeros())});
}

}  // namespace radwalk
