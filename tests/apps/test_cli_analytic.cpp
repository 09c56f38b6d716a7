// The analytic form-factor route end to end (docs/form-factors.md, "The analytic route"): `formfactors
// --analytic` on the closed cube writes an F whose rows sum to 1 and reports its pairs in the JSON summary;
// `solve --analytic` gives the same CSV on 1 and 2 threads; the ray options it cannot honour are refused with
// exit 2, as are --visibility-samples without --analytic or not a power of 2; --analytic-cutoff reports its dropped
// pairs in the JSON summary and is refused without --analytic or outside [0, 1). Reading another program's F: rows
// up to 1 + 1e-3 are used with a warning naming the worst row, --normalise-rows divides them by their sums.
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

TEST_CASE("formfactors and solve --analytic run, report, are thread-independent, refuse ray options",
          "[cli][formfactor][analytic]") {
  const fs::path dir = scratch_dir("analytic");
  const fs::path mtx = dir / "F.mtx", json = dir / "r.json";
  Run r = run("formfactors " + source("meshes/cube.obj") + " --max-edge 0.25 --analytic -o " + mtx.string() +
              " --json " + json.string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  CHECK(text_of(json).find("\"clear_pairs\"") != std::string::npos);
  CHECK(r.out.find("row sums in [1.000000, 1.000000]") != std::string::npos);

  const std::string scene = source("meshes/cornell_box.obj") + " --max-edge 200 --analytic";
  const fs::path csv1 = dir / "one.csv", csv2 = dir / "two.csv";
  REQUIRE(run("solve " + scene + " --threads 1 --csv " + csv1.string()).exit_code == 0);
  REQUIRE(run("solve " + scene + " --threads 2 --csv " + csv2.string()).exit_code == 0);
  CHECK(text_of(csv1) == text_of(csv2));

  for (const std::string bad : {" --rays 100", " --sobol-rays", " --emitter-columns 8", " --rays-per-area 10"}) {
    r = run("solve " + scene + bad);
    INFO(bad << ": " << r.out);
    CHECK(r.exit_code == 2);
    CHECK(r.out.find("--analytic") != std::string::npos);
  }
  r = run("solve " + source("meshes/cornell_box.obj") + " --max-edge 200 --visibility-samples 64");
  CHECK(r.exit_code == 2);
  r = run("solve " + scene + " --visibility-samples 100");
  CHECK(r.exit_code == 2);
  CHECK(r.out.find("power of 2") != std::string::npos);
}

TEST_CASE("formfactors --analytic --analytic-cutoff drops pairs and reports them, refused without --analytic",
          "[cli][formfactor][analytic]") {
  const fs::path dir = scratch_dir("analytic_cutoff");
  const fs::path json = dir / "r.json";
  Run r = run("formfactors " + source("meshes/cube.obj") + " --max-edge 0.1 --analytic --analytic-cutoff 3e-3 --json " +
              json.string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  const std::string j = text_of(json);
  CHECK(j.find("\"dropped_pairs\"") != std::string::npos);
  CHECK(j.find("\"largest_cutoff_bound\"") != std::string::npos);
  r = run("formfactors " + source("meshes/cube.obj") + " --max-edge 0.1 --analytic-cutoff 3e-3");
  CHECK(r.exit_code == 2);
  r = run("formfactors " + source("meshes/cube.obj") + " --max-edge 0.1 --analytic --analytic-cutoff 2");
  CHECK(r.exit_code == 2);
}

TEST_CASE("a read F with rows up to 1 + 1e-3 is used with a warning naming the worst row, or normalised",
          "[cli][formfactor][analytic]") {
  const fs::path dir = scratch_dir("rows_above_one");
  // The cube's 6 faces, every row 0.2 to each other face (sum 1), row 3 (1-based) 1.000015 (View3D's excess).
  std::string text = "%%MatrixMarket matrix coordinate real general\n6 6 30\n";
  for (int i = 1; i <= 6; ++i)
    for (int j = 1; j <= 6; ++j)
      if (i != j) text += std::to_string(i) + " " + std::to_string(j) + (i == 3 && j == 1 ? " 0.200015\n" : " 0.2\n");
  const fs::path mtx = dir / "view3d.mtx";
  std::ofstream(mtx) << text;
  Run r = run("solve " + source("meshes/cube.obj") + " --form-factors " + mtx.string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("largest row 2 (0-based)") != std::string::npos);
  const fs::path json = dir / "r.json";
  r = run("solve " + source("meshes/cube.obj") + " --form-factors " + mtx.string() + " --normalise-rows --json " +
          json.string());
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("largest row") == std::string::npos);
  CHECK(text_of(json).find("\"rows_normalised\": 1") != std::string::npos);
}
