// The form-factor options end to end (docs/form-factors.md): --sobol-rays and --emitter-columns M
// run, report their emitter columns and shadow rays in the JSON summary, give the same CSV on 1 and 2 threads and
// change the result (they are recorded options); a non-positive M is refused with exit 2.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "radwalk_runner.h"

namespace fs = std::filesystem;

namespace {

std::string text_of(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

TEST_CASE("the form-factor options sobol-rays and emitter-columns run, report, are thread-independent, refuse M <= 0",
          "[cli][formfactor]") {
  const fs::path dir = scratch_dir("emitter_columns");
  const std::string scene = source("meshes/cornell_box.obj") + " --max-edge 200 --rays 200";
  const fs::path csv1 = dir / "one.csv", csv2 = dir / "two.csv", plain = dir / "plain.csv", json = dir / "r.json";
  const std::string opts = " --sobol-rays --emitter-columns 64";
  Run r = run("solve " + scene + opts + " --threads 1 --csv " + csv1.string() + " --json " + json.string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  const std::string summary = text_of(json);
  CHECK(summary.find("\"emitter_columns\"") != std::string::npos);
  CHECK(summary.find("\"emitter_shadow_rays\"") != std::string::npos);
  // The same options (the run id in the CSV records them; output names and --threads aside).
  REQUIRE(run("solve " + scene + opts + " --threads 2 --csv " + csv2.string() + " --json " +
              (dir / "r2.json").string())
              .exit_code == 0);
  CHECK(text_of(csv1) == text_of(csv2));
  REQUIRE(run("solve " + scene + " --csv " + plain.string()).exit_code == 0);
  CHECK(text_of(csv1) != text_of(plain));
  r = run("solve " + scene + " --emitter-columns 0");
  CHECK(r.exit_code == 2);
  CHECK(r.out.find("--emitter-columns") != std::string::npos);
}
