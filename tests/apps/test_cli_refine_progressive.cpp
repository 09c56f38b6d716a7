// End-to-end: radwalk solve --refine (adaptive patching) and --progressive (ParaView series of the iterates).
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>

#include "radwalk_runner.h"

namespace fs = std::filesystem;

namespace {

// A fresh folder `name` in this file's scratch folder.
fs::path scratch(const std::string& name) {
  const fs::path dir = scratch_dir("cli_refine_test") / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

// The files a .pvd lists, relative to its folder.
std::vector<std::pair<double, std::string>> pvd_steps(const fs::path& pvd) {
  std::ifstream in(pvd);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::regex entry("timestep=\"([^\"]+)\" part=\"0\" file=\"([^\"]+)\"");
  std::vector<std::pair<double, std::string>> steps;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), entry); it != std::sregex_iterator(); ++it)
    steps.emplace_back(std::stod((*it)[1].str()), (*it)[2].str());
  return steps;
}

}  // namespace

TEST_CASE("radwalk solve --refine: fewer patches than the uniform mesh of the same smallest patches", "[cli]") {
  const fs::path dir = scratch("refine");
  const Run r = run("solve " + source("meshes/cornell_box.obj") + " --refine 0.2 --refine-steps 3 --rays 20000 " +
                    "--json " + (dir / "s.json").string() + " --csv " + (dir / "s.csv").string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  const auto j = read_json(dir / "s.json");
  const auto& refine = j["refine"];
  REQUIRE(refine["steps"].size() == 4);  // 3 refinement steps: 4 solves
  CHECK(refine["stop_reason"] == "steps");
  CHECK(refine["initial_patches"] == 37);
  std::size_t patches = 37;
  for (std::size_t k = 0; k < refine["steps"].size(); ++k) {
    const auto& s = refine["steps"][k];
    CHECK(s["patches"] == patches);
    patches += 3 * s["split"].get<std::size_t>();
    if (k + 1 < refine["steps"].size()) CHECK(s["split"] == s["marked"]);
  }
  CHECK(refine["steps"][3]["split"] == 0);
  const std::size_t final_patches = j["patches"];
  CHECK(final_patches == refine["steps"][3]["patches"]);
  // Splitting every patch 3 times gives 37 x 4^3 patches with the same smallest patches as the refined mesh.
  CHECK(final_patches * 10 < 37 * 64 * 6);  // at most 60 % of them
  // Rows in the CSV = the final patches.
  std::ifstream csv(dir / "s.csv");
  std::string line;
  std::size_t rows = 0;
  std::getline(csv, line);
  CHECK(line.find("jump") != std::string::npos);
  while (std::getline(csv, line)) ++rows;
  CHECK(rows == final_patches);
}

TEST_CASE("radwalk solve --hierarchical: one CSV row and one .vtp cell per leaf, the JSON hierarchy block", "[cli]") {
  const fs::path dir = scratch("hierarchical");
  const Run r = run("solve " + source("meshes/cornell_box.obj") + " --hierarchical --hierarchical-tol 0.01 " +
                    "--hierarchical-rays 20000 --discretisation-directions 2 --json " + (dir / "h.json").string() +
                    " --csv " + (dir / "h.csv").string() + " -o " + (dir / "h.vtp").string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  const auto j = read_json(dir / "h.json");
  const auto& h = j["hierarchy"];
  CHECK(h["roots"] == 37);
  CHECK(h["links"] == 0);
  CHECK(h["clusters"] == 0);
  const std::size_t leaves = h["leaves"], elements = h["elements"];
  CHECK(leaves > 37);  // something was refined
  CHECK(elements == 37 + 4 * ((leaves - 37) / 3));  // every split turns one leaf into four
  CHECK(h["levels"].get<int>() >= 2);
  CHECK(h["memory_bytes"].get<std::size_t>() > 0);
  CHECK(j["patches"] == leaves);
  // Rows: one per leaf, each with its input face; every input face of the scene is there.
  std::ifstream csv(dir / "h.csv");
  std::string line;
  std::getline(csv, line);
  CHECK(line.rfind("patch,face,", 0) == 0);
  CHECK(line.find("B_disc_r") != std::string::npos);
  std::size_t rows = 0;
  std::set<int> faces;
  while (std::getline(csv, line)) {
    ++rows;
    faces.insert(std::stoi(line.substr(line.find(',') + 1)));
  }
  CHECK(rows == leaves);
  CHECK(faces.size() == 37);
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((dir / "h.vtp").string().c_str());
  reader->Update();
  CHECK(static_cast<std::size_t>(reader->GetOutput()->GetNumberOfCells()) == leaves);
}

TEST_CASE("radwalk solve --hierarchical-refine estimate: the budget of leaves, the steps in the JSON, refusals",
          "[cli]") {
  const fs::path dir = scratch("hierarchical_estimate");
  const Run r = run("solve " + source("meshes/cornell_box.obj") + " --hierarchical --hierarchical-refine estimate " +
                    "--hierarchical-max-leaves 120 --hierarchical-rays 40000 --discretisation-directions 2 --json " +
                    (dir / "h.json").string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  const auto j = read_json(dir / "h.json");
  const auto& h = j["hierarchy"];
  CHECK(h["refine"] == "estimate");
  const std::size_t leaves = h["leaves"];
  CHECK(leaves > 37);
  CHECK(leaves <= 120);
  CHECK(h["refinement_steps"]["direct"] == 0);  // the a-priori oracles are off in this mode
  CHECK(h["refinement_steps"]["transport"] == 0);
  const auto& steps = h["estimate_steps"];
  REQUIRE(steps.size() >= 2);
  CHECK(steps[0]["leaves"] == 37);
  CHECK(steps[0]["eta"].get<double>() > 0);
  CHECK(steps.back()["leaves"] == leaves);
  CHECK(h["target_reached"] == false);
  // No stopping rule: refused with one line. --hierarchical-tol has no oracle to drive here: refused.
  const Run none = run("solve " + source("meshes/cornell_box.obj") + " --hierarchical --hierarchical-refine estimate");
  CHECK(none.exit_code != 0);
  CHECK(none.out.find("--hierarchical-max-leaves") != std::string::npos);
  const Run tol = run("solve " + source("meshes/cornell_box.obj") + " --hierarchical --hierarchical-refine estimate " +
                      "--hierarchical-max-leaves 100 --hierarchical-tol 0.01");
  CHECK(tol.exit_code != 0);
  CHECK(tol.out.find("--hierarchical-tol") != std::string::npos);
  const Run budget = run("solve " + source("meshes/cornell_box.obj") + " --hierarchical --hierarchical-max-leaves 100");
  CHECK(budget.exit_code != 0);  // an option of the estimate's mode without it
  CHECK(budget.out.find("--hierarchical-max-leaves") != std::string::npos);
}

TEST_CASE("radwalk solve --refine: --max-patches caps the patch count", "[cli]") {
  const fs::path dir = scratch("refine_cap");
  const Run r = run("solve " + source("meshes/cornell_box.obj") + " --refine 0.01 --max-patches 200 --rays 2000 " +
                    "--json " + (dir / "s.json").string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  const auto j = read_json(dir / "s.json");
  CHECK(j["patches"].get<std::size_t>() <= 200);
  CHECK(j["refine"]["stop_reason"] == "max-patches");
}

TEST_CASE("radwalk solve --refine and --progressive: impossible combinations are one-line errors", "[cli]") {
  const std::string cube = source("meshes/cube.obj");
  for (const std::string args : {" --refine 0.1 --solver random-walk", " --refine 0 ", " --progressive d --solver direct",
                                 " --refine 0.1 --progressive d --solver jacobi"}) {
    const Run r = run("solve " + cube + args);
    INFO(args << ": " << r.out);
    CHECK(r.exit_code == 2);
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') <= 2);
  }
}

TEST_CASE("radwalk solve --progressive writes a .pvd whose step files exist", "[cli]") {
  for (const std::string solver : {"jacobi", "gauss-seidel", "southwell"}) {
    const fs::path dir = scratch("progressive_" + solver);
    const Run r = run("solve " + source("meshes/cornell_box.obj") + " --max-edge 100 --rays 500 --solver " + solver +
                      " --progressive " + (dir / "series").string() + " --json " + (dir / "s.json").string());
    INFO(solver << ": " << r.out);
    REQUIRE(r.exit_code == 0);
    const auto steps = pvd_steps(dir / "series" / "solve.pvd");
    const auto j = read_json(dir / "s.json");
    REQUIRE(!steps.empty());
    CHECK(steps.size() <= 200);
    CHECK(j["progressive"]["steps"] == steps.size());
    for (std::size_t k = 0; k < steps.size(); ++k) {
      CHECK(fs::exists(dir / "series" / steps[k].second));
      if (k > 0) CHECK(steps[k].first > steps[k - 1].first);
    }
    // The last step is the returned iterate.
    CHECK(steps.back().first == j["solution"]["iterations"].get<double>());
    if (solver != "southwell") CHECK(steps.size() == j["solution"]["iterations"].get<std::size_t>());
  }
}

TEST_CASE("radwalk solve --progressive thins a long run to at most 200 steps, keeping the last", "[cli]") {
  // Furnace, 24 patches: Southwell reports every 2 shots and needs a few hundred shots, so the series thins.
  const fs::path dir = scratch("progressive_thin");
  const Run r = run("solve " + source("meshes/furnace.obj") + " --max-edge 0.5 --rays 200 --solver southwell " +
                    "--progressive " + (dir / "series").string() + " --json " + (dir / "s.json").string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  const auto j = read_json(dir / "s.json");
  const auto steps = pvd_steps(dir / "series" / "solve.pvd");
  REQUIRE(j["solution"]["iterations"].get<long>() / 2 > 200);  // more reports than files
  CHECK(j["progressive"]["stride"].get<long>() > 1);
  CHECK(steps.size() <= 200);
  CHECK(steps.back().first == j["solution"]["iterations"].get<double>());
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir / "series")) files += entry.path().extension() == ".vtp";
  CHECK(files == steps.size());  // thinned steps were deleted
}

namespace {

// A field-data value of a .vtp (a number; NaN if absent).
double field_number(const fs::path& vtp, const std::string& name) {
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(vtp.string().c_str());
  reader->Update();
  vtkDataArray* a = reader->GetOutput()->GetFieldData()->GetArray(name.c_str());
  return a ? a->GetComponent(0, 0) : std::nan("");
}

}  // namespace

TEST_CASE("radwalk solve --progressive: every step carries its iteration, residual and elapsed time", "[cli]") {
  const fs::path dir = scratch("progressive_fields");
  const Run r = run("solve " + source("meshes/cornell_box.obj") + " --max-edge 100 --rays 500 --solver jacobi " +
                    "--progressive " + (dir / "series").string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  const auto steps = pvd_steps(dir / "series" / "solve.pvd");
  REQUIRE(steps.size() > 5);
  double last_elapsed = -1;
  for (const auto& [t, file] : steps) {
    const fs::path vtp = dir / "series" / file;
    CHECK(field_number(vtp, "iteration") == t);
    CHECK(field_number(vtp, "elapsed_seconds") >= last_elapsed);
    last_elapsed = field_number(vtp, "elapsed_seconds");
  }
  CHECK(field_number(dir / "series" / steps.front().second, "residual") > 1e-3);
  CHECK(field_number(dir / "series" / steps.back().second, "residual") <= 1e-10);
}

TEST_CASE("radwalk solve --solver random-walk --progressive: the estimate after 1, 2, 4, ... batches", "[cli]") {
  const fs::path dir = scratch("progressive_walks");
  const Run r = run("solve " + source("meshes/cube.obj") + " --rays 2000 --solver random-walk --walks-per-patch 100 " +
                    "--progressive " + (dir / "series").string() + " --csv " + (dir / "b.csv").string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  const auto steps = pvd_steps(dir / "series" / "solve.pvd");
  const std::vector<double> counts = {2, 4, 7, 13, 25, 50, 100};  // ceil(100 / 2^k), k = 6 .. 0
  REQUIRE(steps.size() == counts.size());
  for (std::size_t k = 0; k < steps.size(); ++k) {
    CHECK(steps[k].first == counts[k]);
    CHECK(field_number(dir / "series" / steps[k].second, "count") == counts[k]);
  }
  // The relative standard error falls about as 1 / sqrt(walks): 50 times the walks, about 7 times smaller.
  const double first = field_number(dir / "series" / steps.front().second, "B_se_relative_rms");
  const double last = field_number(dir / "series" / steps.back().second, "B_se_relative_rms");
  CHECK(last < first / 3);
  CHECK(last > first / 20);
}

TEST_CASE("radwalk pathtrace --progressive writes pathtrace.pvd with B and B_se per step", "[cli]") {
  const fs::path dir = scratch("progressive_pt");
  const Run r = run("pathtrace " + source("meshes/cube.obj") + " --spp 32 --progressive " + (dir / "s").string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  const auto steps = pvd_steps(dir / "s" / "pathtrace.pvd");
  REQUIRE(steps.size() == 5);  // 2, 4, 8, 16, 32 samples per patch
  CHECK(steps.front().first == 2);
  CHECK(steps.back().first == 32);
}

TEST_CASE("radwalk --paraview-state: a Python state beside the .vtp, other uses are one-line errors", "[cli]") {
  const fs::path dir = scratch("state");
  const std::string cube = source("meshes/cube.obj");
  const Run ok = run("solve " + cube + " -o " + (dir / "b.vtp").string() + " --paraview-state " +
                     (dir / "b.py").string());
  INFO(ok.out);
  REQUIRE(ok.exit_code == 0);
  std::ifstream in(dir / "b.py");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(text.find("name = 'b.vtp'") != std::string::npos);
  CHECK(text.find("field = 'B'") != std::string::npos);
  CHECK(text.find("title = 'B [W/unit^2]'") != std::string::npos);
  // The one camera rule, pathtrace's fit (apps/scene_camera.h): the closed cube without objects is seen from its
  // centre with a 60 degree field of view, looking at its most lit region (a wall lit by the ceiling's light), as
  // `pathtrace --image` looks at it.
  CHECK(text.find("view.CameraPosition = [0.5, 0.5, 0.5]") != std::string::npos);
  CHECK(text.find("view.CameraViewAngle = 59.99999") != std::string::npos);
  const Run traced = run("pathtrace " + cube + " --spp 2 --image " + (dir / "i.png").string() +
                         " --width 8 --height 8 --json " + (dir / "i.json").string());
  REQUIRE(traced.exit_code == 0);
  std::ifstream js(dir / "i.json");
  const auto camera = nlohmann::json::parse(js)["camera"];
  char focal[160];
  std::snprintf(focal, sizeof focal, "view.CameraFocalPoint = [%.17g, %.17g, %.17g]",
                camera["look_at"][0].get<double>(), camera["look_at"][1].get<double>(),
                camera["look_at"][2].get<double>());
  CHECK(text.find(focal) != std::string::npos);
  for (const std::string& args : {"solve " + cube + " -o " + (dir / "c.vtp").string() + " --paraview-state s.pvsm",
                                 "solve " + cube + " --paraview-state s.py"}) {
    const Run bad = run(args);
    INFO(args << ": " << bad.out);
    CHECK(bad.exit_code == 2);
    CHECK(bad.out.rfind("radwalk: error: ", 0) == 0);
    CHECK(std::count(bad.out.begin(), bad.out.end(), '\n') == 1);
  }
}
