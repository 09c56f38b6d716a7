// Matrix Market: exact round trip of an estimated F, and each refusal with its file:line message.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <limits>
#include <utility>

#include <sys/stat.h>

#include "core/error.h"
#include "formfactor/form_factors.h"
#include "formfactor/form_factor_file.h"
#include "formfactor/matrix_market.h"
#include "formfactor/npz.h"
#include "support/box_scenes.h"
#include "visibility/embree_visibility.h"

using namespace radwalk;

namespace {

std::string temp_path(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("radwalk_mm_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

std::string write_text(const std::string& name, const std::string& text) {
  const std::string path = temp_path(name);
  std::ofstream(path) << text;
  return path;
}

// The InputError message from reading `text` as a 3-patch matrix ("" when it was accepted).
std::string refusal(const std::string& text, std::size_t n = 3) {
  const std::string path = write_text("bad.mtx", text);
  try {
    read_matrix_market(path, n);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const std::string kHeader = "%%MatrixMarket matrix coordinate real general\n";

}  // namespace

TEST_CASE("Matrix Market round trip is exact", "[formfactor]") {
  const PatchSet ps = test::unit_cube_room(2, true);
  const EmbreeVisibility vis(ps);
  FormFactorOptions opt;
  opt.rays_per_patch = 777;  // values like 13/777 need all float digits
  const FormFactors ff = estimate_form_factors(ps, vis, opt);
  const std::string path = temp_path("cube.mtx");
  write_matrix_market(path, ff.F);
  const SparseF back = read_matrix_market(path, ps.size());
  REQUIRE(back.nonZeros() == ff.F.nonZeros());
  const auto nnz = std::size_t(back.nonZeros());
  CHECK(std::equal(back.valuePtr(), back.valuePtr() + nnz, ff.F.valuePtr()));
  CHECK(std::equal(back.innerIndexPtr(), back.innerIndexPtr() + nnz, ff.F.innerIndexPtr()));
  CHECK(std::equal(back.outerIndexPtr(), back.outerIndexPtr() + back.rows() + 1, ff.F.outerIndexPtr()));
  std::ifstream in(path);
  std::string header, comment;
  std::getline(in, header);
  std::getline(in, comment);
  CHECK(header == "%%MatrixMarket matrix coordinate real general");
  CHECK(comment.find("radwalk") != std::string::npos);
  // The wrong patch count is refused.
  CHECK_THROWS_AS(read_matrix_market(path, ps.size() + 1), InputError);
}

TEST_CASE("Matrix Market accepts comments, blank lines and any entry order", "[formfactor]") {
  const std::string path = write_text("ok.mtx", kHeader + "% comment\n\n3 3 3\n3 1 0.25\n1 2 0.5\n% mid\n\n1 3 0.5\n");
  const SparseF F = read_matrix_market(path, 3);
  CHECK(F.coeff(0, 1) == 0.5f);
  CHECK(F.coeff(0, 2) == 0.5f);
  CHECK(F.coeff(2, 0) == 0.25f);
  CHECK(F.nonZeros() == 3);
  // A row sum of 1 + 5e-7 is rounding, accepted; empty matrices are fine.
  CHECK(refusal(kHeader + "3 3 2\n1 2 0.5000005\n1 3 0.5\n").empty());
  CHECK(refusal(kHeader + "3 3 0\n").empty());
}

TEST_CASE("Matrix Market refusals name the file and line", "[formfactor]") {
  const std::string file = temp_path("bad.mtx");
  struct Case {
    const char* what;
    std::string text;
    int line;
    const char* phrase;
  };
  const std::vector<Case> cases = {
      {"empty file", "", 0, "empty"},
      {"no header", "3 3 1\n1 2 0.5\n", 1, "first line"},
      {"array format", "%%MatrixMarket matrix array real general\n3 3\n", 1, "unsupported"},
      {"symmetric", "%%MatrixMarket matrix coordinate real symmetric\n3 3 0\n", 1, "unsupported"},
      {"no size line", kHeader + "% only a comment\n", 2, "missing size"},
      {"malformed size", kHeader + "3 3\n", 2, "size line"},
      {"size with junk", kHeader + "3 3 1 x\n1 2 0.5\n", 2, "size line"},
      {"non-square", kHeader + "3 4 0\n", 2, "not square"},
      {"size mismatch", kHeader + "4 4 0\n", 2, "patches"},
      {"malformed entry", kHeader + "3 3 1\n1 2\n", 3, "malformed entry"},
      {"entry with junk", kHeader + "3 3 1\n1 2 0.5x\n", 3, "malformed entry"},
      {"row zero", kHeader + "3 3 1\n0 2 0.5\n", 3, "out of range"},
      {"column too large", kHeader + "3 3 1\n1 4 0.5\n", 3, "out of range"},
      {"value above 1", kHeader + "3 3 1\n1 2 1.5\n", 3, "[0, 1]"},
      {"negative value", kHeader + "3 3 1\n1 2 -0.1\n", 3, "[0, 1]"},
      {"NaN", kHeader + "3 3 1\n1 2 nan\n", 3, "[0, 1]"},
      {"infinity", kHeader + "3 3 1\n1 2 inf\n", 3, "[0, 1]"},
      {"too few entries", kHeader + "3 3 2\n1 2 0.5\n", 3, "ends after 1 of 2"},
      {"too many entries", kHeader + "3 3 1\n1 2 0.5\n2 1 0.5\n", 4, "more entries"},
      {"duplicate (unsorted)", kHeader + "3 3 3\n2 1 0.5\n1 2 0.25\n2 1 0.25\n", 5, "duplicate"},
      {"duplicate (sorted)", kHeader + "3 3 2\n1 2 0.25\n1 2 0.25\n", 4, "duplicate"},
      {"row sum above 1", kHeader + "3 3 3\n1 2 0.6\n2 1 0.5\n1 3 0.6\n", 3, "sums to"},
      {"entry count out of range", kHeader + "3 3 10\n", 2, "out of range"},
  };
  for (const auto& c : cases) {
    const std::string msg = refusal(c.text);
    const std::string where = c.line > 0 ? file + ":" + std::to_string(c.line) + ":" : file + ":";
    INFO(c.what << ": message '" << msg << "', expected to start with '" << where << "' and mention '" << c.phrase
                << "'");
    CHECK(msg.rfind(where, 0) == 0);
    CHECK(msg.find(c.phrase) != std::string::npos);
    CHECK(msg.find('\n') == std::string::npos);
  }
  CHECK_THROWS_AS(read_matrix_market(temp_path("no_such_file.mtx"), 3), InputError);
  // O1: a two-line file declaring 2^31-1 entries allocated 25.8 GB before reading any entry.
  const std::string huge = refusal(kHeader + "50000 50000 2147483647\n", 50000);
  INFO(huge);
  CHECK(huge.rfind(file + ":2: declares 2147483647 entries, more than a file of", 0) == 0);
}

TEST_CASE("Matrix Market: tiny values are values, FIFOs are refused", "[formfactor]") {
  // P9: 1e-50 was refused as "malformed" (it underflows a float); it is a legal, negligible form factor.
  const SparseF F = read_matrix_market(write_text("tiny.mtx", kHeader + "3 3 2\n1 2 1e-50\n1 3 0.5\n"), 3);
  CHECK(F.nonZeros() == 2);
  CHECK(F.coeff(0, 1) == 0.0f);
  CHECK(F.coeff(0, 2) == 0.5f);
  // H1: a FIFO would block the reader (and a second read of it for error lines).
  const std::string fifo = temp_path("pipe.mtx");
  std::filesystem::remove(fifo);
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  CHECK_THROWS_WITH(read_matrix_market(fifo, 3), Catch::Contains("pipe.mtx") && Catch::Contains("FIFO"));
}

TEST_CASE("Matrix Market: a value below the smallest double is 0, as in every text format", "[formfactor]") {
  // The number rule of mesh/text_scan.h: underflow rounds to 0 ("1e-400" was refused as a malformed entry);
  // overflow is a number out of [0, 1], not a malformed entry.
  const SparseF F = read_matrix_market(write_text("underflow.mtx", kHeader + "3 3 2\n1 2 1e-400\n1 3 0.5\n"), 3);
  CHECK(F.nonZeros() == 2);
  CHECK(F.coeff(0, 1) == 0.0f);
  CHECK(F.coeff(0, 2) == 0.5f);
  const std::string huge = refusal(kHeader + "3 3 1\n1 2 1e400\n");
  INFO(huge);
  CHECK(huge.find("not in [0, 1]") != std::string::npos);
  std::filesystem::remove_all(std::filesystem::path(temp_path("")).parent_path());
}

TEST_CASE("Matrix Market: a malformed line of a megabyte is quoted by its first 80 characters", "[formfactor]") {
  const std::string junk(1 << 20, '7');
  for (const std::string& text : {kHeader + "3 3 1\n1 2 0.5" + junk + "x\n", kHeader + "3 3 " + junk + "x\n",
                                  "%%MatrixMarket matrix coordinate real " + junk + "\n",
                                  kHeader + "3 3 1\n1 2 1" + junk + "\n"}) {
    const std::string message = refusal(text);
    INFO(message.substr(0, 300));
    CHECK(message.find("bad.mtx:") != std::string::npos);
    CHECK(message.size() < 300);
    CHECK(message.find("777...'") != std::string::npos);
  }
  std::filesystem::remove_all(std::filesystem::path(temp_path("")).parent_path());
}

TEST_CASE("write_matrix_market and write_npz refuse a matrix their readers would refuse", "[formfactor]") {
  // A negative entry was written, and the file then refused by read_matrix_market; F's entries are fractions of
  // power, so the writers refuse what the readers refuse, in one line naming the file and the entry, writing
  // nothing.
  const auto F_with = [](float a, float b) {
    SparseF F(3, 3);
    F.insert(0, 1) = a;
    F.insert(1, 2) = b;
    F.makeCompressed();
    return F;
  };
  for (const char* name : {"w.mtx", "w.npz"}) {
    const std::string path = temp_path(name);
    std::filesystem::remove(path);
    const bool npz = std::string(name) == "w.npz";
    const auto write = [&](const SparseF& F) { npz ? write_npz(path, F) : write_matrix_market(path, F); };
    for (const auto& [F, phrase] :
         {std::pair<SparseF, std::string>{F_with(-0.25f, 0.5f), "F(0, 1) = -0.25 is not in [0, 1]"},
          {F_with(0.25f, std::numeric_limits<float>::quiet_NaN()), "F(1, 2) = nan is not in [0, 1]"},
          {F_with(0.25f, 1.5f), "F(1, 2) = 1.5 is not in [0, 1]"}}) {
      try {
        write(F);
        FAIL(name << ": written");
      } catch (const InputError& e) {
        const std::string message = e.what();
        INFO(message);
        CHECK(message.rfind(path + ": not a form-factor matrix: ", 0) == 0);
        CHECK(message.find(phrase) != std::string::npos);
      }
      CHECK(!std::filesystem::exists(path));
    }
    SparseF over(3, 3);
    over.insert(2, 0) = 0.75f;
    over.insert(2, 1) = 0.5f;
    CHECK_THROWS_WITH(write(over), Catch::Contains("row 2 (0-based) sums to 1.25"));
    // What they write, they read back.
    write(F_with(0.25f, 1.0f));
    CHECK(read_form_factors(path, 3).coeff(1, 2) == 1.0f);
  }
  std::filesystem::remove_all(std::filesystem::path(temp_path("")).parent_path());
}

TEST_CASE("rows of another program's F up to 1 + 1e-3: read, named, normalised on request, and beyond refused",
          "[formfactor][io]") {
  // Row 0 sums to 1 + 1.5e-5 (View3D's excess on the unit cube), row 1 to 1 + 4e-4, row 2 to 0.9; a file with a
  // row at 1 + 2e-3 is refused.
  const std::string path = write_text("over.mtx", kHeader + "3 3 5\n1 2 0.600015\n1 3 0.4\n2 1 0.5004\n2 3 0.5\n3 1 0.9\n");
  SparseF F = read_matrix_market(path, 3);
  const RowsAboveOne above = rows_above_one(F, kRoundingRowSum);
  CHECK(above.count == 2);
  CHECK(above.worst == 1);
  CHECK(above.worst_sum == Approx(1.0004).epsilon(1e-6));
  CHECK(normalise_rows(F) == 2);
  for (Eigen::Index i = 0; i < 2; ++i) {
    double sum = 0;
    for (SparseF::InnerIterator it(F, i); it; ++it) sum += it.value();
    CHECK(sum <= kRoundingRowSum);
    CHECK(sum == Approx(1.0).epsilon(1e-6));
  }
  CHECK(F.coeff(2, 0) == 0.9f);  // a row below 1 is left alone
  CHECK(rows_above_one(F, kRoundingRowSum).count == 0);
  const std::string exactly_one = write_text("exactly_one.mtx", kHeader + "2 2 2\n1 2 1\n2 1 1\n");
  CHECK_NOTHROW(read_matrix_market(exactly_one, 2));
  const std::string refused = write_text("refused.mtx", kHeader + "2 2 3\n1 2 0.502\n1 1 0.5\n2 1 1\n");
  CHECK_THROWS_WITH(read_matrix_market(refused, 2), Catch::Contains("above 1 + 1e-3"));
}
