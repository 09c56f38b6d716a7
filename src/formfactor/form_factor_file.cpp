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

}  // namespace radwalk
