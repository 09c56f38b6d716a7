// The failure hook of the statistical checks (artifacts.h, stat_checks.h): a rejecting z-test writes its table as
// CSV and the per-patch z as .vtp, a rejecting chi-square test its counts, and the failure message names the
// files. The failing checks run in a child process (the hidden case below, run by name), so the suite passes.
#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

#include "support/artifacts.h"
#include "support/box_scenes.h"
#include "support/stat_checks.h"

using namespace radwalk;

namespace {

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

// Hidden ("[.]"): not part of any run unless named. One entry of 18 is 9 standard errors off, and 100 : 0 counts
// are far from 50 : 50.
TEST_CASE("failure hook demo: a rejected z-test table and a rejected chi-square test", "[.][failure-hook-demo]") {
  const PatchSet patches = test::unit_cube_room(1);
  test::ZTable table("demo z", 3.0);
  for (Eigen::Index i = 0; i < 6; ++i)
    for (int c = 0; c < 3; ++c)
      table.add_patch(i, c, "patch " + std::to_string(i) + " channel " + std::to_string(c),
                      i == 2 && c == 1 ? 10.0 : 1.0, 1.0, 1.0);
  table.check(&patches);
  test::check_chi_square("demo chi-square", {100, 0}, {50, 50}, 1e-3);
}

TEST_CASE("a failing statistical check writes its tables and names them in the message", "[support]") {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("radwalk-failure-hook-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
  const std::string command =
      "RADWALK_TEST_ARTIFACTS='" + dir.string() + "' '" + self + "' '[failure-hook-demo]' 2>&1";
  FILE* child = ::popen(command.c_str(), "r");
  REQUIRE(child);
  std::string output;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, child)) output += buffer;
  const int status = ::pclose(child);
  INFO(output);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) != 0);  // the demo's checks failed

  const std::string stem = "failure_hook_demo__a_rejected_z-test_table_and_a_rejected_chi-square_test--";
  const std::filesystem::path z_csv = dir / (stem + "demo_z.csv"), z_vtp = dir / (stem + "demo_z.vtp"),
                              chi_csv = dir / (stem + "demo_chi-square.csv");
  for (const auto& path : {z_csv, z_vtp, chi_csv}) {
    INFO(path);
    CHECK(std::filesystem::exists(path));
    CHECK(output.find(path.string()) != std::string::npos);  // the failure message says where
  }
  const std::string z_table = read_file(z_csv);
  CHECK(z_table.rfind("entry,estimate,se,expected,z,z_critical,rejected\n", 0) == 0);
  CHECK(z_table.find("patch 2 channel 1,10,1,1,9,3,1\n") != std::string::npos);
  CHECK(z_table.find("patch 0 channel 0,1,1,1,0,3,0\n") != std::string::npos);
  CHECK(read_file(chi_csv) == "bin,observed,expected,contribution\n0,100,50,50\n1,0,50,50\n");
  CHECK(read_file(z_vtp).find("<VTKFile") != std::string::npos);
  std::filesystem::remove_all(dir);
}
