#pragma once
// A form-factor file, its format chosen by the extension: ".npz" is binary CSR (npz.h: scipy.sparse.load_npz
// reads it, radwalk reads it into F in pieces), anything else Matrix Market text (matrix_market.h, for interchange).
#include <cstddef>
#include <string>

#include "formfactor/form_factor_rows.h"
#include "formfactor/sparse_f.h"

namespace radwalk {

// True when `path` names an .npz file (by its extension).
bool is_npz_path(const std::string& path);

// write_npz or write_matrix_market by the extension of `path`.
void write_form_factors(const std::string& path, const SparseF& F, const std::string& run_id = "");

// read_npz or read_matrix_market by the extension of `path`; InputError as they refuse. With `rows` over MPI,
// each rank keeps only its block of rows (blocks of about equal non-zeros into *rows; form_factor_rows.h).
SparseF read_form_factors(const std::string& path, std::size_t expected_n, RowBlocks* rows = nullptr);

}  // namespace radwalk
