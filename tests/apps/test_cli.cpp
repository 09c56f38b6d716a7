// End-to-end: the radwalk program on bundled scenes and on every malformed input in tests/data.
#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <algorithm>
#include <sstream>
#include <vector>
#include <string>

#include "radwalk_runner.h"

namespace fs = std::filesystem;

namespace {

fs::path scratch() { return scratch_dir("cli_test"); }

}  // namespace

TEST_CASE("radwalk check: the Cornell box is clean", "[cli]") {
  const Run r = run("check " + source("meshes/cornell_box.obj"));
  INFO(r.out);
  CHECK(r.exit_code == 0);
  CHECK(r.out.find("clean") != std::string::npos);
}

TEST_CASE("radwalk check: every malformed input gives a one-line error or a warning, never a crash",
          "[cli]") {
  for (const auto& entry : fs::directory_iterator(source("tests/data"))) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".obj" && ext != ".ply") continue;
    const Run r = run("check " + entry.path().string());
    INFO(entry.path().filename().string() << " -> exit " << r.exit_code << ": " << r.out);
    // 0 (repaired, with warnings) or 2 (refused): never a signal, never an internal error.
    CHECK((r.exit_code == 0 || r.exit_code == 2));
    if (r.exit_code == 2) {
      // One line, prefixed, naming the file; a file with several errors lists each on its own such line, then
      // counts them in one (tests/apps/test_cli_findings.cpp). --quiet: the warnings are only counted.
      const long lines = std::count(r.out.begin(), r.out.end(), '\n');
      CHECK(r.out.rfind("radwalk: error: ", 0) == 0);
      CHECK((lines == 1 || r.out.find(": refused: ") != std::string::npos));
      std::istringstream in(r.out);
      for (std::string line; std::getline(in, line);)
        CHECK(line.rfind("radwalk: error: ", 0) == 0);
      CHECK(r.out.find(entry.path().filename().string()) != std::string::npos);
    } else {
      CHECK(r.out.find("warning(s) not shown (--quiet)") != std::string::npos);
    }
  }
}

TEST_CASE("radwalk: bad options and missing files exit 2", "[cli]") {
  CHECK(run("check /nonexistent/scene.obj").exit_code == 2);
  CHECK(run("solve " + source("meshes/cube.obj") + " --solver nonsense").exit_code == 2);
  CHECK(run("patch " + source("meshes/cube.obj") + " -o out.stl").exit_code == 2);
  CHECK(run("").exit_code == 2);
}

TEST_CASE("radwalk: bad option values and outputs in missing directories give one prefixed line", "[cli]") {
  const std::string cube = source("meshes/cube.obj");
  for (const std::string& args : {"solve " + cube + " --rays abc", "solve " + cube + " --max-edge inf",
                                 "solve " + cube + " --tol -1", "solve " + cube + " --bogus", std::string(""),
                                 "solve " + cube + " -q -o /nonexistent-dir/b.vtp",
                                 "solve " + cube + " -q --csv /nonexistent-dir/b.csv",
                                 // P3, I6, O5: saturated, overflowing and absurd counts.
                                 "solve " + cube + " --seed -1", "solve " + cube + " --threads 2147483647",
                                 "pathtrace " + cube + " --spp 9223372036854775807",
                                 "compare " + cube + " --rays 100 --walks-per-patch 9223372036854775807",
                                 "solve " + cube + " --rays 100 --solver random-walk --walks-per-patch 100000000000000",
                                 // P12, P13: a patch listed twice; a field of view out of range, in degrees.
                                 "solve " + cube + " --rays 100 --solver random-walk --patches 1 1 1",
                                 "pathtrace " + cube + " --image " + (scratch() / "x.png").string() +
                                     " --camera 0 0 0 0 0 1 0 1 0 200"}) {
    const Run r = run(args);
    INFO("radwalk " << args << " -> exit " << r.exit_code << ": " << r.out);
    CHECK(r.exit_code == 2);
    CHECK(r.out.rfind("radwalk: error: ", 0) == 0);
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
  }
}

TEST_CASE("radwalk solve: the furnace gives B = E / (1 - rho) = 2 pi on every patch", "[cli]") {
  // Direct solve of the estimated F. The closed furnace is exact for any F whose rows sum to 1, and the
  // closed cube's rows sum to 1 exactly (no ray leaks), so B must equal 2 pi to the solver's precision.
  const fs::path csv = scratch() / "furnace.csv", json = scratch() / "furnace.json";
  const Run r = run("solve " + source("meshes/furnace.obj") + " --max-edge 0.5 --rays 200 --csv " + csv.string() +
                    " --json " + json.string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  REQUIRE(line.find("B_r,B_g,B_b") != std::string::npos);
  // The columns by name (the header's).
  const auto columns = [](const std::string& text) {
    std::vector<std::string> cells;
    std::stringstream ss(text);
    for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
    return cells;
  };
  const std::vector<std::string> header = columns(line);
  const auto index = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  REQUIRE(index("B_b") < header.size());
  REQUIRE(index("B_se_b") < header.size());
  int rows = 0;
  while (std::getline(in, line)) {
    ++rows;
    const std::vector<std::string> cells = columns(line);
    CHECK(std::stod(cells[index("B_b")]) == Approx(2 * M_PI).epsilon(1e-6));
    // Every row of F sums to 1 and B is the same everywhere, so the rays' noise moves no gather: B_se = 0 up to
    // the rounding of B (float F), checked at B's own precision.
    CHECK(std::stod(cells[index("B_se_b")]) <= 1e-6 * 2 * M_PI);
  }
  CHECK(rows == 24);  // 6 faces x 2 x 2
  std::ifstream js(json);
  const auto j = nlohmann::json::parse(js);
  CHECK(j["solution"]["status"] == "converged");
  CHECK(j["patches"] == 24);
  CHECK(j["timings_s"].contains("form_factors"));
  // Typed values (docs/json-schema.md): counts are integers, the seed has its own field.
  CHECK(j["schema_version"].is_number_integer());
  CHECK(j["git_describe"].is_string());
  CHECK(j["seed"] == 1);
  CHECK(j["schema_version"] == 2);
  CHECK(j["rays_total"].is_number_integer());
  CHECK(j["rays_total"] == 24 * 200);  // total vs per patch: the key names which
  CHECK(j["rays_per_patch"] == 200);
  CHECK(j["solution"]["info"]["factorisations"].is_number_integer());
  CHECK(j["solution"]["info"]["dense"].is_boolean());
  for (const auto& [key, value] : j.items()) CHECK(key.find(' ') == std::string::npos);
  for (const auto& [key, value] : j["timings_s"].items()) CHECK(key.find(' ') == std::string::npos);
}

TEST_CASE("radwalk formfactors writes a Matrix Market file that solve reads back", "[cli]") {
  const fs::path mtx = scratch() / "cube.mtx";
  const Run ff = run("formfactors " + source("meshes/cube.obj") + " --rays 2000 -o " + mtx.string());
  INFO(ff.out);
  REQUIRE(ff.exit_code == 0);
  const Run solve = run("solve " + source("meshes/cube.obj") + " --form-factors " + mtx.string());
  INFO(solve.out);
  CHECK(solve.exit_code == 0);
  // A size mismatch is refused.
  const Run bad = run("solve " + source("meshes/cube.obj") + " --max-edge 0.5 --form-factors " + mtx.string());
  INFO(bad.out);
  CHECK(bad.exit_code == 2);
  CHECK(bad.out.find("cube.mtx") != std::string::npos);
}

TEST_CASE("radwalk patch -o .obj writes a scene that loads back as the same patches", "[cli]") {
  const fs::path obj = scratch() / "cornell_patched.obj";
  const fs::path csv1 = scratch() / "patched_direct.csv", csv2 = scratch() / "patched_reloaded.csv";
  // With the contact cut (the default): the floor pieces under the blocks close the blocks' open shells in the
  // written file, and read back facing up as written (the file's "# radwalk_as_written" line).
  const Run r = run("patch " + source("meshes/cornell_box.obj") + " --max-edge 100 -o " +
                    obj.string() + " --csv " + csv1.string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  REQUIRE(fs::exists(scratch() / "cornell_patched.mtl"));
  const Run back = run("patch " + obj.string() + " -o " + (scratch() / "again.vtp").string() + " --csv " +
                       csv2.string());
  INFO(back.out);
  REQUIRE(back.exit_code == 0);
  // Same patches in the same order with the same area, rho and E (the face column differs: each patch is now an
  // input face of its own).
  std::ifstream a(csv1), b(csv2);
  std::string la, lb;
  int rows = 0;
  std::getline(a, la);
  std::getline(b, lb);
  while (std::getline(a, la) && std::getline(b, lb)) {
    ++rows;
    auto cells = [](const std::string& line) {
      std::vector<std::string> out;
      std::stringstream ss(line);
      for (std::string c; std::getline(ss, c, ',');) out.push_back(c);
      return out;
    };
    const auto x = cells(la), y = cells(lb);
    REQUIRE(x.size() == y.size());
    // The last column is the run id, which differs (other input, other options).
    REQUIRE(x.back().size() == 16);
    CHECK(x.back() != y.back());
    // Numbers within rounding; the names (object, group, material: the OBJ's o, g and usemtl) as they were.
    for (std::size_t k = 2; k + 1 < x.size(); ++k) {
      if (k >= 15 && k <= 17)
        CHECK(x[k] == y[k]);
      else
        CHECK(std::stod(x[k]) == Approx(std::stod(y[k])).margin(1e-9));
    }
  }
  CHECK(rows == 360);
}

TEST_CASE("radwalk: no output overwrites an input or another output", "[cli]") {
  // D3: --csv cube.obj, -o same.vtp --csv same.vtp, and patch a.obj -o shared.obj rewriting the shared.mtl that
  // a.obj reads were all accepted (the extension check now also refuses the first two; the rest are refused by
  // comparing files). Every refusal: exit 2, one line naming the file and both roles, nothing written.
  const fs::path dir = scratch() / "distinct";
  fs::create_directories(dir);
  for (const char* f : {"cube.obj", "cube.mtl"}) fs::copy_file(source(std::string("meshes/") + f), dir / f,
                                                             fs::copy_options::overwrite_existing);
  fs::copy_file(dir / "cube.obj", dir / "other.obj", fs::copy_options::overwrite_existing);  // also uses cube.mtl
  const std::string cube = (dir / "cube.obj").string();
  fs::remove(dir / "link.obj");
  fs::create_symlink("cube.obj", dir / "link.obj");
  struct Case {
    std::string args, expected;
  };
  for (const Case& c : {Case{"patch " + cube + " -o " + cube, "-o would overwrite the scene"},
                        Case{"patch " + cube + " -o " + (dir / "link.obj").string(), "-o would overwrite the scene"},
                        Case{"patch " + (dir / "other.obj").string() + " -o " + cube,
                             "cube.mtl: -o (its .mtl) would overwrite the scene's material library"}}) {
    INFO(c.args);
    const auto before = fs::last_write_time(dir / "cube.mtl");
    const Run r = run(c.args);
    CHECK(r.exit_code == 2);
    CHECK(r.out.find(c.expected) != std::string::npos);
    CHECK(r.out.find("radwalk never writes over an input") != std::string::npos);
    CHECK(fs::last_write_time(dir / "cube.mtl") == before);
  }
  // Distinct outputs beside the scene are fine.
  const Run same = run("solve " + cube + " -o " + (dir / "s.vtp").string() + " --paraview-state " +
                       (dir / "s.py").string() + " --csv " + (dir / "s.csv").string());
  CHECK(same.exit_code == 0);
}

TEST_CASE("radwalk compare --json: total walks, walks per estimate, the run seeds, spread and mean variance (schema 2)",
          "[cli]") {
  const fs::path json = scratch() / "compare.json";
  const Run r = run("compare " + source("meshes/cube.obj") + " --rays 200 --estimators gather-collision,shoot-absorption"
                    " --walks-per-patch 30 --runs 3 --seed 7 -q --json " + json.string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  std::ifstream js(json);
  const auto j = nlohmann::json::parse(js);
  CHECK(j["schema_version"] == 2);
  CHECK(j["seed"] == 7);
  CHECK(j["compare"]["runs"] == 3);
  CHECK(j["compare"]["walks_per_patch"] == 30);
  CHECK(j["compare"]["kernel"] == "matrix");
  CHECK(j["compare"]["walk_seeds"] == nlohmann::json::array({7, 8, 9}));
  const auto n = j["patches"].get<long>();
  const auto& g = j["estimators"]["gather-collision"];
  CHECK(g["walks_per_estimate"] == 3 * 30);      // R x walks per patch
  CHECK(g["walks_total"] == 3 * 30 * n);        // over every estimated patch
  const auto& s = j["estimators"]["shoot-absorption"];
  CHECK(s["walks_per_estimate"] == 3 * 30 * n);  // every particle scores every patch
  CHECK(s["walks_total"] == 3 * 30 * n);
  for (const auto* e : {&g, &s}) {
    for (const char* key : {"runs", "steps", "seconds", "mean_abs_z", "max_abs_z", "var_over_theory", "spread_over_se",
                            "mean_var_per_walk", "efficiency"})
      CHECK(e->contains(key));
    for (const char* old : {"walks", "var_ratio"}) CHECK_FALSE(e->contains(old));
    CHECK((*e)["spread_over_se"].get<double>() > 0);
    CHECK((*e)["mean_var_per_walk"].get<double>() > 0);
  }
}
