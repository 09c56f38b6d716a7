// Binary form factors (.npz, npz.h): exact round trip of an estimated F, the layout scipy reads (aligned arrays),
// and each refusal of a bad or hostile file in one line naming the file.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/error.h"
#include "core/input_file.h"
#include "formfactor/form_factor_file.h"
#include "formfactor/form_factors.h"
#include "formfactor/matrix_market.h"
#include "formfactor/npz.h"
#include "support/box_scenes.h"
#include "visibility/embree_visibility.h"

using namespace radwalk;

namespace {

std::string temp_path(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("radwalk_npz_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

// A 3 x 3 F: row 0 = (0, 0.25, 0.5), row 1 = (0.125, 0, 0), row 2 empty.
SparseF small_F() {
  SparseF F(3, 3);
  F.insert(0, 1) = 0.25f;
  F.insert(0, 2) = 0.5f;
  F.insert(1, 0) = 0.125f;
  F.makeCompressed();
  return F;
}

// The InputError message from reading `bytes` as a 3-patch .npz ("" when accepted).
std::string refusal(const std::string& bytes, std::size_t n = 3) {
  const std::string path = temp_path("bad.npz");
  write_bytes(path, bytes);
  try {
    read_npz(path, n);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// `bytes` with the first occurrence of `from` replaced by `to` (same length).
std::string patched(std::string bytes, const std::string& from, const std::string& to) {
  REQUIRE(from.size() == to.size());
  const std::size_t at = bytes.find(from);
  REQUIRE(at != std::string::npos);
  bytes.replace(at, from.size(), to);
  return bytes;
}

// The bytes write_npz writes for F.
std::string npz_of(const SparseF& F) {
  const std::string path = temp_path("made.npz");
  write_npz(path, F);
  return read_bytes(path);
}

bool one_line(const std::string& s) { return !s.empty() && s.find('\n') == std::string::npos; }

std::uint64_t le(const std::string& b, std::size_t at, int width) {
  std::uint64_t v = 0;
  for (int k = width - 1; k >= 0; --k) v = v << 8 | static_cast<unsigned char>(b[at + std::size_t(k)]);
  return v;
}

void put_le32(std::string& b, std::size_t at, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) b[at + std::size_t(k)] = char((v >> (8 * k)) & 0xff);
}

// CRC-32 (the zip polynomial, bit by bit: independent of the zlib the reader uses).
std::uint32_t crc32_of(const char* p, std::size_t n) {
  std::uint32_t c = 0xffffffffu;
  for (std::size_t i = 0; i < n; ++i) {
    c ^= static_cast<unsigned char>(p[i]);
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
  }
  return ~c;
}

// `bytes` (as write_npz writes them: ZIP64 records, no comment) with every member's CRC-32 recomputed in its local
// header and directory entry: a file edited on purpose, which only the checks of its content can refuse.
std::string with_crcs_fixed(std::string bytes) {
  const std::size_t end64 = bytes.size() - 22 - 20 - 56;
  REQUIRE(le(bytes, end64, 4) == 0x06064b50u);
  std::size_t at = le(bytes, end64 + 48, 8);
  for (std::uint64_t m = le(bytes, end64 + 32, 8); m > 0; --m) {
    REQUIRE(le(bytes, at, 4) == 0x02014b50u);
    const std::size_t name = le(bytes, at + 28, 2), extra = le(bytes, at + 30, 2), comment = le(bytes, at + 32, 2);
    const std::size_t zip64 = at + 46 + name;  // the ZIP64 extra field: id, length, size, packed size, offset
    const std::size_t size = le(bytes, zip64 + 4, 8), local = le(bytes, zip64 + 20, 8);
    const std::size_t data = local + 30 + le(bytes, local + 26, 2) + le(bytes, local + 28, 2);
    const std::uint32_t crc = crc32_of(bytes.data() + data, size);
    put_le32(bytes, at + 16, crc);
    put_le32(bytes, local + 14, crc);
    at += 46 + name + extra + comment;
  }
  return bytes;
}

// The file of F with its first stored value `from` (in data.npy, the last array) changed to `to`.
std::string with_value(const std::string& bytes, float from, float to) {
  std::string a(4, '\0'), b(4, '\0');
  std::memcpy(a.data(), &from, 4);
  std::memcpy(b.data(), &to, 4);
  std::string out = bytes;
  const std::size_t at = out.find(a, out.rfind("\x93NUMPY"));
  REQUIRE(at != std::string::npos);
  out.replace(at, 4, b);
  return out;
}

}  // namespace

TEST_CASE("npz round trip is exact, and the extension chooses the format", "[formfactor][npz]") {
  const PatchSet ps = test::unit_cube_room(2, true);
  const EmbreeVisibility vis(ps);
  FormFactorOptions opt;
  opt.rays_per_patch = 777;
  const FormFactors ff = estimate_form_factors(ps, vis, opt);
  const std::string path = temp_path("cube.npz");
  write_form_factors(path, ff.F, "0123456789abcdef");
  const SparseF back = read_form_factors(path, ps.size());
  REQUIRE(back.rows() == ff.F.rows());
  REQUIRE(back.nonZeros() == ff.F.nonZeros());
  const auto nnz = std::size_t(back.nonZeros());
  CHECK(std::equal(back.valuePtr(), back.valuePtr() + nnz, ff.F.valuePtr()));
  CHECK(std::equal(back.innerIndexPtr(), back.innerIndexPtr() + nnz, ff.F.innerIndexPtr()));
  CHECK(std::equal(back.outerIndexPtr(), back.outerIndexPtr() + back.rows() + 1, ff.F.outerIndexPtr()));
  // A zip (local header signature first), not Matrix Market text; the same F through .mtx reads back equal.
  CHECK(read_bytes(path).substr(0, 4) == std::string("PK\x03\x04", 4));
  const std::string mtx = temp_path("cube.mtx");
  write_form_factors(mtx, ff.F);
  CHECK(read_bytes(mtx).substr(0, 14) == "%%MatrixMarket");
  const SparseF via_mtx = read_form_factors(mtx, ps.size());
  CHECK(std::equal(via_mtx.valuePtr(), via_mtx.valuePtr() + nnz, back.valuePtr()));
  // Every member's array data is 64-byte aligned in the file (mappable in place): the .npy headers end there.
  const std::string bytes = read_bytes(path);
  for (std::size_t at = bytes.find("\x93NUMPY"); at != std::string::npos; at = bytes.find("\x93NUMPY", at + 1)) {
    const std::size_t header = std::size_t(static_cast<unsigned char>(bytes[at + 8])) |
                               std::size_t(static_cast<unsigned char>(bytes[at + 9])) << 8;
    CHECK((at + 10 + header) % 64 == 0);
  }
  CHECK_THROWS_AS(read_npz(path, ps.size() + 1), InputError);
}

TEST_CASE("npz: an empty matrix and empty rows round trip", "[formfactor][npz]") {
  SparseF empty(4, 4);
  empty.makeCompressed();
  const std::string path = temp_path("empty.npz");
  write_npz(path, empty);
  CHECK(read_npz(path, 4).nonZeros() == 0);
  write_npz(path, small_F());
  const SparseF back = read_npz(path, 3);
  CHECK(back.coeff(0, 2) == 0.5f);
  CHECK(back.coeff(1, 0) == 0.125f);
  CHECK(back.nonZeros() == 3);
}

TEST_CASE("npz: bad and hostile files are refused in one line naming the file", "[formfactor][npz]") {
  const std::string good = npz_of(small_F());
  REQUIRE(refusal(good).empty());
  const auto refused = [](const std::string& message, const std::string& part) {
    INFO(message);
    CHECK(one_line(message));
    CHECK(message.find("bad.npz") != std::string::npos);
    CHECK(message.find(part) != std::string::npos);
  };
  SECTION("not a zip, empty, truncated") {
    refused(refusal("%%MatrixMarket matrix coordinate real general\n"), "not a .npz");
    refused(refusal(""), "not a .npz");
    for (std::size_t cut : {good.size() - 1, good.size() / 2, std::size_t(100), std::size_t(21)})
      CHECK(one_line(refusal(good.substr(0, cut))));
    // Cut inside the data but the directory kept: the members point past the end, or their bytes disagree.
    std::string hole = good;
    hole.erase(200, 40);
    CHECK(one_line(refusal(hole)));
  }
  SECTION("wrong dtype") {
    refused(refusal(patched(good, "'<f4'", "'<f2'")), "dtype '<f2'");
    refused(refusal(patched(good, "'<i4'", "'>i4'")), "dtype '>i4'");
  }
  SECTION("wrong shape or size") {
    refused(refusal(good, 4), "but there are 4 patches");
    refused(refusal(patched(good, "'shape': (4,)", "'shape': (5,)")), "(truncated?)");  // indptr of N + 1 = 4
    refused(refusal(patched(good, "'fortran_order': False", "'fortran_order': True ")), "Fortran");
    refused(refusal(patched(good, "csr", "csc")), "not 'csr'");
  }
  SECTION("indices out of range, non-monotone indptr, bad values, unsorted rows, row sums") {
    SparseF F = small_F();
    F.innerIndexPtr()[1] = 7;
    refused(refusal(npz_of(F)), "out of range");
    F = small_F();
    F.innerIndexPtr()[1] = -1;
    refused(refusal(npz_of(F)), "out of range");
    F = small_F();
    F.outerIndexPtr()[1] = 3;  // row 0 = 3 entries, row 1 = 0 .. then indptr[2] = 3: fine; make it decrease
    F.outerIndexPtr()[2] = 1;
    refused(refusal(npz_of(F)), "decreases");
    F = small_F();
    std::swap(F.innerIndexPtr()[0], F.innerIndexPtr()[1]);
    refused(refusal(npz_of(F)), "not strictly increasing");
    // Values the writer refuses: the stored 0.25 changed in the file (with its CRC-32 made right again).
    refused(refusal(with_crcs_fixed(with_value(good, 0.25f, 1.5f))), "not in [0, 1]");
    refused(refusal(with_crcs_fixed(with_value(good, 0.25f, std::numeric_limits<float>::quiet_NaN()))),
            "not in [0, 1]");
    refused(refusal(with_crcs_fixed(with_value(good, 0.25f, 0.75f))), "sums to");
    REQUIRE(refusal(with_crcs_fixed(with_value(good, 0.25f, 0.375f))).empty());
  }
  SECTION("a missing member") {  // renamed in the local header and the central directory
    refused(refusal(patched(patched(good, "data.npy", "date.npy"), "data.npy", "date.npy")), "no member data.npy");
  }
}

TEST_CASE("npz: a file truncated while it is read is refused as changed, not killed by SIGBUS", "[formfactor][npz]") {
  // The reader mapped the file: truncated by another process meanwhile, the next access to a mapped page past the
  // new end killed radwalk with SIGBUS and no message. It now reads in pieces; the test truncates the file right
  // after the reader's first read (a seam of core/input_file.h), which is deterministic.
  const std::string path = temp_path("shrinks.npz");
  write_npz(path, small_F());
  const std::string bytes = read_bytes(path);
  for (const std::size_t keep : {std::size_t(0), std::size_t(100), bytes.size() / 2, bytes.size() - 1}) {
    write_bytes(path, bytes);
    int reads = 0;
    set_input_piece_observer([&](const std::string& p, std::uint64_t, std::size_t) {
      if (p == path && ++reads == 1) std::filesystem::resize_file(path, keep);
    });
    std::string message;
    try {
      read_npz(path, 3);
    } catch (const InputError& e) {
      message = e.what();
    }
    set_input_piece_observer({});
    INFO("kept " << keep << " bytes: " << message);
    CHECK(message == path + ": changed while it was read (it is shorter now)");
  }
  std::filesystem::remove_all(std::filesystem::path(path).parent_path());
}

TEST_CASE("npz: a file rewritten in place while it is read is refused as changed", "[formfactor][npz]") {
  // Same size, another byte and a later modification time: found by the size and time check after the last read
  // (when the CRC-32 of the member does not find it first).
  const std::string path = temp_path("rewritten.npz");
  write_npz(path, small_F());
  const std::string bytes = read_bytes(path);
  const timespec old_times[2] = {{946684800, 0}, {946684800, 0}};  // 2000-01-01: any later write changes it
  REQUIRE(::utimensat(AT_FDCWD, path.c_str(), old_times, 0) == 0);
  bool done = false;
  set_input_piece_observer([&](const std::string& p, std::uint64_t, std::size_t) {
    if (p != path || done) return;
    done = true;
    std::fstream f(path, std::ios::binary | std::ios::in | std::ios::out);
    f.seekp(std::streamoff(bytes.size() - 1));
    f.put(bytes.back());  // the same byte: only the modification time tells
  });
  std::string message;
  try {
    read_npz(path, 3);
  } catch (const InputError& e) {
    message = e.what();
  }
  set_input_piece_observer({});
  CHECK(message == path + ": changed while it was read (its size or modification time differ)");
  std::filesystem::remove_all(std::filesystem::path(path).parent_path());
}

TEST_CASE("npz: a value changed inside [0, 1] is refused by the member's CRC-32", "[formfactor][npz]") {
  // Every value was checked, none was compared with the CRC-32 the file carries (scipy checks it): a valid value
  // changed in the file was solved with.
  const std::string good = npz_of(small_F());
  const std::string message = refusal(with_value(good, 0.25f, 0.375f));
  INFO(message);
  CHECK(message == temp_path("bad.npz") +
                       ": member data.npy: CRC-32 mismatch (the file is corrupt, or was changed after it was written)");
  // Any member: a column index changed within range, the shape's bytes.
  std::string index = good;
  const std::size_t indices = index.find("\x93NUMPY");  // indices.npy is the first member write_npz writes
  const std::size_t first = indices + 10 + le(index, indices + 8, 2);
  REQUIRE(le(index, first, 4) == 1);  // row 0's first column
  index[first] = 0;
  CHECK_THAT(refusal(index), Catch::Contains("member indices.npy: CRC-32 mismatch"));
  CHECK(refusal(with_crcs_fixed(index)).empty());  // column 0 of row 0: a valid matrix, once the CRC is right
  std::filesystem::remove_all(std::filesystem::path(temp_path("")).parent_path());
}

TEST_CASE("npz: declared counts beyond N^2 or rows longer than N are refused before allocation", "[formfactor][npz]") {
  // A 6-patch F declaring more non-zeros than N^2 was allocated at its declared size first (a sparse file of
  // 16 GiB declares 2^31 - 1: exit 4, out of memory). Now refused from indptr and the headers alone.
  const auto F_with_rows = [](std::initializer_list<int> lengths) {
    SparseF F(6, 6);
    std::int32_t* outer = F.outerIndexPtr();
    outer[0] = 0;
    int i = 0;
    for (const int n : lengths) outer[i + 1] = outer[i] + n, ++i;
    F.resizeNonZeros(outer[6]);
    std::fill(F.innerIndexPtr(), F.innerIndexPtr() + outer[6], 0);
    std::fill(F.valuePtr(), F.valuePtr() + outer[6], 0.0f);
    return F;
  };
  const std::string too_many = refusal(npz_of(F_with_rows({7, 6, 6, 6, 6, 6})), 6);
  INFO(too_many);
  CHECK(too_many == temp_path("bad.npz") + ": 37 non-zeros declared, more than the 36 entries of a 6 x 6 matrix");
  const std::string too_long = refusal(npz_of(F_with_rows({0, 7, 0, 0, 0, 0})), 6);
  INFO(too_long);
  CHECK(too_long == temp_path("bad.npz") + ": row 1 has 7 non-zeros, more than the 6 columns");
  std::filesystem::remove_all(std::filesystem::path(temp_path("")).parent_path());
}
