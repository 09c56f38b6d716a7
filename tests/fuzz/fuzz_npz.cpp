// Fuzz harness: the .npz reader and writer of form-factor matrices (formfactor/npz.h).
//
// Input: the bytes of one .npz file. read_npz reads a path, so the bytes are written to a temporary file in a
// directory of this process's own ($TMPDIR, else /dev/shm, else /tmp: radwalk-fuzz-npz-PID/, removed at exit).
// The expected patch count is the first number of the file's shape.npy array, found by a scan of its own (the
// first .npy array whose header declares shape (2,) after a member name "shape.npy"; 3 when there is none),
// capped at kMaxPatches: a caller's patch count is bounded, a file's declaration is not.
// Each input is read twice: as it is, and with every member's CRC-32 recomputed (when the zip directory can be
// walked), since a mutation almost never keeps a CRC-32 right and the checks behind it would go unfuzzed.
// Contract: read_npz returns a SparseF or throws InputError; write_npz writes what it is given.
// Oracles:
//   (a) a refusal is one line of printable UTF-8 that starts with the file's path; nothing but InputError, no
//       crash, no allocation above 512 MB (scripts/fuzz.sh: -malloc_limit_mb=512);
//   (c) an accepted matrix is expected_n x expected_n, compressed, with the CSR invariants (offsets from 0 to
//       nnz and monotone, columns in range and strictly increasing within a row, values in [0, 1], row sums <=
//       kMaxRowSum); write_npz then read_npz gives it back exactly (offsets, columns, the bits of every value).
#include <zlib.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "formfactor/npz.h"
#include "form_factor_oracles.h"
#include "fuzz_scratch.h"
#include "fuzz_support.h"

using namespace radwalk;
using namespace radwalk::fuzz;

namespace {

constexpr std::int64_t kMaxPatches = 100'000;

std::uint64_t le(std::string_view b, std::size_t at, int width) {
  std::uint64_t v = 0;
  for (int k = width - 1; k >= 0; --k) v = v << 8 | static_cast<unsigned char>(b[at + std::size_t(k)]);
  return v;
}

// The declared N: the first int64 (or int32) of the .npy array after the name "shape.npy".
std::int64_t declared_n(std::string_view b) {
  const std::size_t name = b.find("shape.npy");
  if (name == std::string_view::npos) return 3;
  const std::size_t magic = b.find("\x93NUMPY", name);
  if (magic == std::string_view::npos || magic + 10 > b.size()) return 3;
  const std::size_t header = le(b, magic + 8, 2), data = magic + 10 + header;
  if (data + 8 > b.size()) return 3;
  const bool int32 = b.substr(magic, 10 + header).find("<i4") != std::string_view::npos;
  const std::int64_t n = int32 ? std::int64_t(std::int32_t(le(b, data, 4))) : std::int64_t(le(b, data, 8));
  return std::clamp<std::int64_t>(n, 0, kMaxPatches);
}

// The bytes with every member's CRC-32 (directory entry and local header) recomputed over the member's bytes, or
// nothing when the end record, the directory or a local header cannot be walked within the bytes.
std::optional<std::string> with_crcs_recomputed(std::string b) {
  if (b.size() < 22) return std::nullopt;
  const std::size_t end = b.size() - 22;
  if (le(b, end, 4) != 0x06054b50u) return std::nullopt;
  std::uint64_t count = le(b, end + 10, 2), dir = le(b, end + 16, 4);
  if (end >= 76 && le(b, end - 20, 4) == 0x07064b50u && le(b, end - 76, 4) == 0x06064b50u) {
    count = le(b, end - 76 + 32, 8);
    dir = le(b, end - 76 + 48, 8);
  }
  std::uint64_t at = dir;
  for (std::uint64_t m = 0; m < count && m < 64; ++m) {
    if (at > b.size() || b.size() - at < 46 || le(b, at, 4) != 0x02014b50u) return std::nullopt;
    const std::uint64_t name = le(b, at + 28, 2), extra = le(b, at + 30, 2), comment = le(b, at + 32, 2);
    if (b.size() - at - 46 < name + extra + comment) return std::nullopt;
    std::uint64_t usize = le(b, at + 24, 4), size = le(b, at + 20, 4), local = le(b, at + 42, 4);
    for (std::uint64_t x = at + 46 + name; x + 4 <= at + 46 + name + extra;) {
      const std::uint64_t id = le(b, x, 2), len = le(b, x + 2, 2);
      if (x + 4 + len > at + 46 + name + extra) return std::nullopt;
      std::uint64_t y = x + 4;
      for (std::uint64_t* field : {&usize, &size, &local})
        if (id == 1 && *field == 0xffffffffu && y + 8 <= x + 4 + len) *field = le(b, y, 8), y += 8;
      x += 4 + len;
    }
    if (local > b.size() || b.size() - local < 30) return std::nullopt;
    const std::uint64_t data = local + 30 + le(b, local + 26, 2) + le(b, local + 28, 2);
    if (data > b.size() || size > b.size() - data) return std::nullopt;
    const auto crc = static_cast<std::uint32_t>(
        crc32(0, reinterpret_cast<const Bytef*>(b.data() + data), static_cast<uInt>(size)));
    for (const std::uint64_t where : {at + 16, local + 14})
      for (int k = 0; k < 4; ++k) b[where + std::uint64_t(k)] = char((crc >> (8 * k)) & 0xff);
    at += 46 + name + extra + comment;
  }
  return b;
}

void check_round_trip(const SparseF& F, std::size_t n) {
  const std::string path = (scratch_directory("npz") / "round_trip.npz").string();
  write_npz(path, F);
  SparseF G;
  const bool read_back = accepts([&] { G = read_npz(path, n); }, {path});
  RADWALK_FUZZ_CHECK(read_back, "radwalk refuses the file it wrote");
  check_same_matrix(F, G);
}

void read_one(std::string_view bytes, const std::string& name, std::size_t n) {
  const std::string path = (scratch_directory("npz") / name).string();
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out.flush()) fail("cannot write the temporary " + path);
  }
  SparseF F;
  if (!accepts([&] { F = read_npz(path, n); }, {path})) return;
  check_form_factor_csr(F, n);
  check_round_trip(F, n);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes = as_text(data, size);
  const auto n = static_cast<std::size_t>(declared_n(bytes));
  read_one(bytes, "input.npz", n);
  if (const auto fixed = with_crcs_recomputed(std::string(bytes))) read_one(*fixed, "crc_fixed.npz", n);
  return 0;
}
