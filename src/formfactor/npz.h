#pragma once
// Form-factor matrices as binary CSR in the .npz layout of scipy.sparse.save_npz(path, F, compressed=False), so
// that numpy and scipy read them directly (scipy.sparse.load_npz) and radwalk reads them back without a parse.
//
// The file is a zip archive (ZIP64 records, so members may exceed 4 GiB) whose members are stored, not
// compressed, each a .npy array (format version 1.0, little endian, C order):
//   indices.npy  int32 '<i4', shape (nnz,)   column j of each non-zero, row by row, increasing within a row
//   indptr.npy   int32 '<i4', shape (N + 1,) row i's non-zeros are indices[indptr[i] .. indptr[i+1])
//   data.npy     float32 '<f4', shape (nnz,) F_ij (row i = patch i, column j = patch j, both 0-based)
//   shape.npy    int64 '<i8', shape (2,)     (N, N)
//   format.npy   bytes '|S3', shape ()       b'csr'
//   run_id.npy   bytes '|S16', shape ()      the run id (apps/run_metadata.h), when given; scipy ignores it
// Each member's array data starts at a multiple of 64 bytes of the file (the zip "extra" field pads the local
// header), so a reader may map the arrays in place. Members carry their CRC-32 (zlib) as zip requires.
//
// Read: in pieces of at most 1 MiB with pread (never mapped, so a file truncated while it is read is an error, not
// a SIGBUS), straight into the CSR: memory is F's own plus that one buffer. Accepted besides what write_npz
// writes: indices and indptr as int64 ('<i8'), data as float64 ('<f8', rounded to float), format as '<U3', any
// member order, npy format versions 1.0, 2.0 and 3.0; other members are ignored. Refused with one InputError
// "FILE: what" (the file and the member), and everything Python's zipfile and numpy.load refuse is refused too,
// so that what radwalk accepts scipy.sparse.load_npz reads as the same matrix: not a zip archive or truncated
// (end record missing, a member past the end of the file), a central directory that does not end where the end
// records start, inconsistent member counts or local headers, encrypted or compressed members (save with
// compressed=False), a missing member, a .npy header that is malformed (numpy's dictionary, parsed strictly; at
// most 10000 bytes) or of another dtype or shape, Fortran order, a format other than csr, a shape that is not
// N x N for the expected patch count (or above the 32-bit index range), more non-zeros than N^2, indptr not
// starting at 0, decreasing, a row longer than N or not ending at nnz (all checked before anything proportional
// to a declared count is allocated), column indices out of range or not strictly increasing within a row
// (unsorted or duplicate: call F.sum_duplicates() first), values not finite or outside [0, 1], rows summing above
// kMaxRowSum (matrix_market.h), a member whose CRC-32 differs from its directory entry's, and a file that changed
// while it was read (shorter than at the start, or another size or modification time at the end: "FILE: changed
// while it was read").
#include <cstddef>
#include <string>

#include "formfactor/form_factor_rows.h"
#include "formfactor/sparse_f.h"

namespace radwalk {

// Writes F atomically (core/atomic_write.h) as described above; run_id: when not empty, the run_id.npy member.
// Refuses what check_writable_form_factors (matrix_market.h) refuses: a file radwalk would not read back.
void write_npz(const std::string& path, const SparseF& F, const std::string& run_id = "");

// Reads an .npz form-factor file of an expected_n x expected_n matrix; InputError as described above. With
// `row_blocks` over MPI (R > 1 ranks), row-distributed (form_factor_rows.h): *row_blocks gets blocks of about equal
// non-zeros from indptr (checked whole on every rank), and this rank checks and copies only the entries of its own
// block, the other rows left empty (a refusal in another rank's rows is found by that rank:
// distributed::agree_on_input_error makes it every rank's; every rank reads every byte of the arrays, for their
// CRC-32). Without `row_blocks`, or with one process, every row.
SparseF read_npz(const std::string& path, std::size_t expected_n, RowBlocks* row_blocks = nullptr);

}  // namespace radwalk
