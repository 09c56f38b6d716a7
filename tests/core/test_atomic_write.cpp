// Atomic writes: the target appears complete or not at all.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/atomic_write.h"
#include "core/error.h"

using namespace radwalk;

TEST_CASE("write_atomically writes the content and leaves no temporary file", "[io]") {
  const auto dir = std::filesystem::temp_directory_path() / "radwalk_atomic_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "out.txt").string();
  write_atomically(path, [](std::ostream& out) { out << "hello\n"; });
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  CHECK(ss.str() == "hello\n");
  CHECK(std::distance(std::filesystem::directory_iterator(dir), {}) == 1);

  // A writer that throws leaves the old file untouched and no temporary behind.
  CHECK_THROWS(write_atomically(path, [](std::ostream& out) {
    out << "partial";
    throw InputError("boom");
  }));
  std::ifstream again(path);
  std::stringstream ss2;
  ss2 << again.rdbuf();
  CHECK(ss2.str() == "hello\n");
  CHECK(std::distance(std::filesystem::directory_iterator(dir), {}) == 1);
  std::filesystem::remove_all(dir);
}

TEST_CASE("write_atomically names the path when the directory does not exist", "[io]") {
  try {
    write_atomically("/nonexistent-dir/x.csv", [](std::ostream&) {});
    FAIL("no exception");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("/nonexistent-dir/x.csv") != std::string::npos);
  }
}
