// Every test program leaves the temporary directory as it found it (scratch_tmpdir.cpp): what a passing run wrote
// there is gone afterwards, and a failing run keeps its files in one named folder. The demo case runs in a child
// process (by name) with TMPDIR pointed at a fresh empty folder, so the check sees exactly what one run leaves.
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

struct ChildRun {
  int exit_code = -1;
  std::string output;
};

// Runs this test program on the hidden demo case with TMPDIR = tmpdir (and the demo told to fail when asked).
ChildRun run_demo(const fs::path& tmpdir, bool fail) {
  const std::string self = fs::read_symlink("/proc/self/exe").string();
  const std::string command = "TMPDIR='" + tmpdir.string() + "' RADWALK_SCRATCH_DEMO_FAIL=" + (fail ? "1" : "0") +
                              " '" + self + "' '[scratch-demo]' 2>&1";
  ChildRun run;
  FILE* child = ::popen(command.c_str(), "r");
  REQUIRE(child);
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, child)) run.output += buffer;
  const int status = ::pclose(child);
  REQUIRE(WIFEXITED(status));
  run.exit_code = WEXITSTATUS(status);
  return run;
}

std::vector<fs::path> entries(const fs::path& dir) {
  std::vector<fs::path> found;
  for (const auto& e : fs::directory_iterator(dir)) found.push_back(e.path());
  return found;
}

}  // namespace

// Hidden ("[.]"): writes a file where tests write theirs, and fails when RADWALK_SCRATCH_DEMO_FAIL=1.
TEST_CASE("scratch demo: a test writes a temporary file", "[.][scratch-demo]") {
  const fs::path file = fs::temp_directory_path() / "written_by_a_test.txt";
  std::ofstream(file) << "scratch\n";
  REQUIRE(fs::exists(file));
  const char* fail = std::getenv("RADWALK_SCRATCH_DEMO_FAIL");
  CHECK(std::string(fail ? fail : "0") == "0");
}

TEST_CASE("a passing test run leaves the temporary directory as it found it, a failing one keeps one named folder",
          "[support]") {
  const fs::path tmpdir = fs::temp_directory_path() / ("radwalk-scratch-check-" + std::to_string(::getpid()));
  fs::remove_all(tmpdir);
  fs::create_directories(tmpdir);

  const ChildRun pass = run_demo(tmpdir, false);
  INFO(pass.output);
  CHECK(pass.exit_code == 0);
  CHECK(entries(tmpdir).empty());

  const ChildRun fail = run_demo(tmpdir, true);
  INFO(fail.output);
  CHECK(fail.exit_code != 0);
  const std::vector<fs::path> kept = entries(tmpdir);
  REQUIRE(kept.size() == 1);
  CHECK(kept[0].filename().string().rfind("radwalk-test-", 0) == 0);
  CHECK(fs::exists(kept[0] / "written_by_a_test.txt"));
  CHECK(fail.output.find("kept scratch folder " + kept[0].string()) != std::string::npos);

  fs::remove_all(tmpdir);
}
