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

// Rows of F summing above `limit` (kRoundingRowSum, matrix_market.h, for what rounding cannot explain): how many,
// and the one with the largest sum (worst = -1 when none). For F read from other programs, whose rows may exceed 1
// by their integration error.
struct RowsAboveOne {
  std::size_t count = 0;
  long long worst = -1;
  double worst_sum = 0;
};
RowsAboveOne rows_above_one(const SparseF& F, double limit);

// Divides every row summing above kRoundingRowSum by its sum (F_ij / sum_j F_ij), so no row exceeds 1 beyond float
// rounding; returns how many rows were divided. Reciprocity A_i F_ij = A_j F_ji changes by the same factors.
std::size_t normalise_rows(SparseF& F);

}  // namespace radwalk
