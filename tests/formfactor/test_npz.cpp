// Binary form factors (.npz, npz.h): exact round trip of an estimated F, the layout scipy reads (aligned arrays),
// and each refusal of a bad or hostile file in one line naming the file.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/error.h"
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
    F = small_F();
    F.valuePtr()[0] = 1.5f;
    refused(refusal(npz_of(F)), "not in [0, 1]");
    F = small_F();
    F.valuePtr()[0] = std::numeric_limits<float>::quiet_NaN();
    refused(refusal(npz_of(F)), "not in [0, 1]");
    F = small_F();
    F.valuePtr()[0] = 0.75f;
    refused(refusal(npz_of(F)), "sums to");
  }
  SECTION("a missing member") {  // renamed in the local header and the central directory
    refused(refusal(patched(patched(good, "data.npy", "date.npy"), "data.npy", "date.npy")), "no member data.npy");
  }
}
