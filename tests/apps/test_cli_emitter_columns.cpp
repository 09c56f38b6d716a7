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

TEST_CASE("the form-factor options sobol-rays and emitter-columns run, report, are thread-independent, refuse M < 0",
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
  REQUIRE(run("solve " + scene + " --no-sobol-rays --emitter-columns 0 --csv " + plain.string()).exit_code == 0);
  CHECK(text_of(csv1) != text_of(plain));
  for (const char* bad : {"-1", "abc", "3.5"}) {
    r = run("solve " + scene + " --emitter-columns " + bad);
    CHECK(r.exit_code == 2);
    CHECK(r.out.find("--emitter-columns") != std::string::npos);
  }
}

TEST_CASE("the defaults are the recommended route: Sobol rays and emitter columns of a third of the rays, off where "
          "every row would need more samples than that or the emitters are large",
          "[cli][formfactor]") {
  const fs::path dir = scratch_dir("emitter_defaults");
  const std::string scene = source("meshes/cornell_box.obj") + " --max-edge 100";
  const fs::path json = dir / "d.json", by_default = dir / "d.csv", spelled = dir / "s.csv";
  Run r = run("solve " + scene + " --rays 300 --json " + json.string() + " --csv " + by_default.string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  std::string summary = text_of(json);
  CHECK(summary.find("\"emitter_samples\": 100") != std::string::npos);
  CHECK(summary.find("\"emitter_columns\": 4") != std::string::npos);
  // Spelled out, the same run (the CSV's values; its run id records the options as given).
  REQUIRE(run("solve " + scene + " --rays 300 --sobol-rays --emitter-columns 100 --csv " + spelled.string()).exit_code == 0);
  const auto values = [](const std::string& csv) {  // every line without its last column, the run id
    std::istringstream in(csv);
    std::string line, out;
    while (std::getline(in, line)) out += line.substr(0, line.rfind(',')) + "\n";
    return out;
  };
  CHECK(values(text_of(by_default)) == values(text_of(spelled)));
  // 4 emitter patches, rays 6: M = 2 < 4, so auto leaves the emitter columns to the cosine rays, and says so.
  r = run("solve " + scene + " --rays 6 --json " + json.string());
  REQUIRE(r.exit_code == 0);
  summary = text_of(json);
  CHECK(summary.find("\"emitter_samples\": 0") != std::string::npos);
  // Every patch of the closed cube emits (a furnace): large emitters keep the cosine rays' rows, which sum to 1.
  r = run("solve " + source("meshes/cube.obj") + " --set white.Ke=1 --json " + json.string());
  REQUIRE(r.exit_code == 0);
  CHECK(text_of(json).find("\"emitter_samples_choice\": \"off: the emitters cover 100 % of the area") != std::string::npos);
  CHECK(summary.find("\"emitter_samples_choice\": \"off: 4 emitter patches, more than the 2 shadow samples") !=
        std::string::npos);
}
