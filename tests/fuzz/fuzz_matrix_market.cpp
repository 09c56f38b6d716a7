// Fuzz harness: the Matrix Market reader and writer of form-factor matrices (formfactor/matrix_market.h).
//
// Input: the bytes of one .mtx file. read_matrix_market streams from a path, so the bytes are written to a
// temporary file in a directory of this process's own ($TMPDIR, else /dev/shm, else /tmp:
// radwalk-fuzz-mm-PID/, removed at exit). The expected patch count is the row count the file declares (read
// here by a scan of its own: the first line that is not the header, a comment or blank), capped at
// kMaxPatches: a caller's patch count is bounded, a file's declaration is not, so a larger declaration meets
// the size check.
// Contract: read_matrix_market returns a SparseF or throws InputError; write_matrix_market writes what it is
// given.
// Oracles:
//   (a) a refusal is one line of printable UTF-8 that starts with the file's path;
//   (c) an accepted matrix is expected_n x expected_n, compressed, with the declared number of entries and
//       the CSR invariants: offsets from 0 to nnz and monotone, columns in range and strictly increasing
//       within a row, values in [0, 1], row sums <= kMaxRowSum; and write_matrix_market then
//       read_matrix_market gives it back exactly (offsets, columns and the bits of every value).

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "form_factor_oracles.h"
#include "formfactor/matrix_market.h"
#include "fuzz_scratch.h"
#include "fuzz_support.h"

using namespace radwalk;
using namespace radwalk::fuzz;

namespace {

constexpr long long kMaxPatches = 100'000;

// The three integers of the size line, as far as they parse (0 otherwise).
struct Declared {
  long long rows = 0, entries = 0;
};
Declared declared_size(std::string_view text) {
  std::size_t at = text.find('\n');
  while (at != std::string_view::npos) {
    const std::size_t start = at + 1;
    at = text.find('\n', start);
    const std::string line(
        text.substr(start, at == std::string_view::npos ? std::string_view::npos : at - start));
    if (line.empty() || line[0] == '%' || line.find_first_not_of(" \t\r") == std::string::npos) continue;
    char* end = nullptr;
    Declared d;
    d.rows = std::strtoll(line.c_str(), &end, 10);
    std::strtoll(end, &end, 10);
    d.entries = std::strtoll(end, &end, 10);
    return d;
  }
  return {};
}

void check_csr(const SparseF& F, std::size_t n, long long entries) {
  RADWALK_FUZZ_CHECK(F.nonZeros() == entries, "entries: " + std::to_string(F.nonZeros()) + " read, " +
                                                  std::to_string(entries) + " declared");
  check_form_factor_csr(F, n);
}

void check_round_trip(const SparseF& F, std::size_t n) {
  const std::string path = (scratch_directory("mm") / "round_trip.mtx").string();
  write_matrix_market(path, F);
  SparseF G;
  const bool read_back = accepts([&] { G = read_matrix_market(path, n); }, {path});
  RADWALK_FUZZ_CHECK(read_back, "radwalk refuses the file it wrote");
  check_same_matrix(F, G);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text = as_text(data, size);
  const std::string path = (scratch_directory("mm") / "input.mtx").string();
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    if (!out.flush()) fail("cannot write the temporary " + path);
  }
  const Declared declared = declared_size(text);
  const auto n = static_cast<std::size_t>(std::clamp(declared.rows, 0LL, kMaxPatches));
  SparseF F;
  if (!accepts([&] { F = read_matrix_market(path, n); }, {path})) return 0;
  check_csr(F, n, declared.entries);
  check_round_trip(F, n);
  return 0;
}
