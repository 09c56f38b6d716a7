#pragma once
// Form-factor matrices as Matrix Market files ("coordinate real general", 1-based indices).
//
// Written: the header line, a comment naming radwalk and the convention (row i, column j: F_ij = fraction of the
// power leaving patch i that arrives at the front of patch j), "N N nnz", then one "i j value" line per non-zero
// in row-major order. Values are the shortest decimal that reads back to the same float (std::to_chars), so a
// round trip is exact. The file is written atomically (core/atomic_write.h).
//
// Read: refuses with a one-line InputError "FILE:LINE: what" a missing or malformed header (anything other than
// "matrix coordinate real general"), a malformed size or entry line, a non-square matrix or one whose size is not
// the expected patch count, indices out of range, duplicate entries, values that are not finite or lie outside
// [0, 1], too few or too many entries, and rows summing above 1 + 1e-3 (kMaxRowSum). An estimated row of radwalk
// sums to at most 1 exactly (counts / n_i), and storing entries as floats moves the sum by at most 2^-24 relative
// (6e-8), so radwalk's own rows stay within kRoundingRowSum = 1 + 1e-6; other programs' F (View3D's adaptive
// integration) exceed 1 by up to about 1e-5. Rows in (kRoundingRowSum, kMaxRowSum] are read as they are: the
// caller warns about them, naming the worst row, or normalises them (form_factor_file.h, rows_above_one and
// normalise_rows; the CLI's --normalise-rows). A larger excess means the file is not a form-factor matrix (or
// was rescaled wrongly). Comment lines (%) and blank lines after the header are skipped. Entries in any order are accepted.
//
// Both directions report progress ("reading form factors", "writing form factors": core/progress.h) by entries.
#include <cstddef>
#include <string>

#include "formfactor/form_factor_rows.h"
#include "formfactor/sparse_f.h"

namespace radwalk {

// Largest row sum the readers (and writers) accept.
inline constexpr double kMaxRowSum = 1.0 + 1e-3;
// Largest row sum that float rounding of a row summing to at most 1 explains.
inline constexpr double kRoundingRowSum = 1.0 + 1e-6;

// What both form-factor readers accept of F's values, checked before a writer writes a byte: every entry finite
// and in [0, 1], every row summing to at most kMaxRowSum, F square. Otherwise InputError "PATH: not a form-factor
// matrix: ...", naming the entry or row (a negative or NaN entry from a caller's matrix would give a file that
// radwalk refuses to read back, far from the cause; F's entries are fractions of power, so the writer refuses it).
void check_writable_form_factors(const std::string& path, const SparseF& F);

// run_id: when not empty, the comment line "% run_id RUN_ID" after the banner (apps/run_metadata.h). Refuses what
// check_writable_form_factors refuses.
void write_matrix_market(const std::string& path, const SparseF& F, const std::string& run_id = "");

// With `row_blocks` over MPI (R > 1 ranks), row-distributed (form_factor_rows.h): a first pass over the file
// checks every entry and counts each row's, *row_blocks gets blocks of about equal non-zeros, and a second pass
// keeps this rank's rows only (duplicates and row sums are checked there, by the rank that holds the row).
SparseF read_matrix_market(const std::string& path, std::size_t expected_n, RowBlocks* row_blocks = nullptr);

}  // namespace radwalk
