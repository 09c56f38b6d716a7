#include "formfactor/form_factor_file.h"

#include <filesystem>

#include "formfactor/matrix_market.h"
#include "formfactor/npz.h"

namespace radwalk {

bool is_npz_path(const std::string& path) { return std::filesystem::path(path).extension() == ".npz"; }

void write_form_factors(const std::string& path, const SparseF& F, const std::string& run_id) {
  if (is_npz_path(path))
    write_npz(path, F, run_id);
  else
    write_matrix_market(path, F, run_id);
}

SparseF read_form_factors(const std::string& path, std::size_t expected_n, RowBlocks* rows) {
  return is_npz_path(path) ? read_npz(path, expected_n, rows) : read_matrix_market(path, expected_n, rows);
}

RowsAboveOne rows_above_one(const SparseF& F, double limit) {
  RowsAboveOne r;
  for (Eigen::Index i = 0; i < F.outerSize(); ++i) {
    double sum = 0;
    for (SparseF::InnerIterator it(F, i); it; ++it) sum += it.value();
    if (sum > limit) {
      ++r.count;
      if (sum > r.worst_sum) r.worst_sum = sum, r.worst = i;
    }
  }
  return r;
}

std::size_t normalise_rows(SparseF& F) {
  std::size_t divided = 0;
  for (Eigen::Index i = 0; i < F.outerSize(); ++i) {
    double sum = 0;
    for (SparseF::InnerIterator it(F, i); it; ++it) sum += it.value();
    if (!(sum > kRoundingRowSum)) continue;
    ++divided;
    for (SparseF::InnerIterator it(F, i); it; ++it) it.valueRef() = float(it.value() / sum);
  }
  return divided;
}

}  // namespace radwalk
