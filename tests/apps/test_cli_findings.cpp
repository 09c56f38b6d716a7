// radwalk and its scene findings: every defect reported in one run, grouped by kind,
// --json written on refusal, -q silencing warnings but keeping their count; --set and --rho-scale giving
// byte for byte the results of the edited MTL.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "radwalk_runner.h"
#include "run_id_reader.h"

namespace fs = std::filesystem;

namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// run() without --quiet.
Run run_loud(const std::string& args) {
  const std::string cmd = std::string(RADWALK_BINARY) + " " + args + " 2>&1";
  Run r{-1, {}};
  FILE* pipe = popen(cmd.c_str(), "r");
  REQUIRE(pipe != nullptr);
  char buf[4096];
  while (std::fgets(buf, sizeof buf, pipe)) r.out += buf;
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// The Cornell box with its MTL edited: `white` (the first block) given this Kd line, or every Kd halved.
fs::path edited_cornell_box(const fs::path& dir, const std::string& white_kd, bool halve_all) {
  fs::copy_file(source("meshes/cornell_box.obj"), dir / "cornell_box.obj", fs::copy_options::overwrite_existing);
  std::string mtl = slurp(source("meshes/cornell_box.mtl"));
  auto replace = [&](const std::string& from, const std::string& to) {
    const auto at = mtl.find(from);
    REQUIRE(at != std::string::npos);
    mtl.replace(at, from.size(), to);
  };
  if (!white_kd.empty()) replace("Kd 0.725 0.71 0.68", white_kd);
  if (halve_all) {
    replace("Kd 0.725 0.71 0.68", "Kd 0.3625 0.355 0.34");
    replace("Kd 0.63 0.065 0.05", "Kd 0.315 0.0325 0.025");
    replace("Kd 0.14 0.45 0.091", "Kd 0.07 0.225 0.0455");
    replace("Kd 0.78 0.78 0.78", "Kd 0.39 0.39 0.39");
  }
  std::ofstream(dir / "cornell_box.mtl", std::ios::binary) << mtl;
  return dir / "cornell_box.obj";
}

}  // namespace

TEST_CASE("radwalk check: self-intersecting faces are split and coplanar overlaps reported, each naming its faces",
          "[cli][findings]") {
  const std::string eight = source("tests/data/self_intersecting_polygon.obj");
  const Run r = run_loud("check " + eight);
  INFO(r.out);
  CHECK(r.exit_code == 0);
  CHECK(contains(r.out, eight + ":17: face 0: polygon with 6 vertices crosses itself: split at 1 crossing into 2 "
                        "simple pieces of area 4 in all"));
  CHECK(contains(r.out, "(object 'eight', material 'light')"));
  CHECK(contains(r.out, eight + ":20: face 1: quad crosses itself: split at 1 crossing into 2 simple pieces of area "
                        "0.5 in all"));
  const Run strict = run_loud("check " + eight + " --strict");
  INFO(strict.out);
  CHECK(strict.exit_code == 2);
  CHECK(contains(strict.out, "face 1: self-intersecting or folded quad"));

  const std::string overlap = source("tests/data/coplanar_overlap.obj");
  const Run o = run_loud("check " + overlap);
  INFO(o.out);
  CHECK(o.exit_code == 0);
  CHECK(contains(o.out, overlap + ":18: face 0: coplanar overlapping faces: this face and face 1 at line 21 (object "
                        "'decal', material 'white') lie in one plane and overlap in area 1, facing the same way"));
  CHECK(!contains(o.out, "face 2 at line"));  // the neighbour shares an edge only
}

TEST_CASE("radwalk check: several defects are all reported in one run, grouped, and --json is written on refusal",
          "[cli][findings]") {
  const fs::path dir = scratch_dir("findings");
  const std::string json = (dir / "refused.json").string();
  const Run r = run_loud("check " + source("tests/data/many_defects.obj") + " --json " + json);
  INFO(r.out);
  CHECK(r.exit_code == 2);
  // Errors of every kind, grouped: 10 bad indices named, then the count of the rest; one summary line last.
  CHECK(contains(r.out, "radwalk: error: " + source("tests/data/many_defects.obj") + ":32: face 1: bad vertex index"));
  CHECK(contains(r.out, "bad vertex index: 2 more (12 in all)"));
  CHECK(contains(r.out, "face 19: unknown material 'no_such_material' (usemtl at line 50"));  // given the default
  CHECK(contains(r.out, "non-finite coordinate"));
  CHECK(contains(r.out, "self-intersecting or folded quad"));
  CHECK(contains(r.out, "duplicate face"));
  CHECK(contains(r.out, "reflectance out of range"));
  CHECK(contains(r.out, "radwalk: warning: "));  // the repairs, found in the same run
  CHECK(contains(r.out, "polygon with 5 vertices triangulated"));
  CHECK(contains(r.out, "refused: 15 errors (12 bad vertex index"));
  const std::string last = r.out.substr(r.out.rfind('\n', r.out.size() - 2) + 1);
  CHECK(contains(last, "refused: 15 errors"));

  REQUIRE(fs::exists(json));
  const auto j = nlohmann::json::parse(slurp(json));
  CHECK(j["refused"] == true);
  CHECK(j["finding_counts"]["error"] == 15);
  // With the triangle 5 5 6 and the copy of face 0, dropped, the unknown material given the default and the
  // copy of that face, dropped.
  CHECK(j["finding_counts"]["repair"] == 6);
  REQUIRE(j["findings"].is_array());
  long bad = 0;
  for (const auto& f : j["findings"]) {
    for (const char* key : {"kind", "severity", "file", "line", "face", "object", "group", "material", "message"})
      CHECK(f.contains(key));
    if (f["kind"] == "bad vertex index") {
      ++bad;
      CHECK(f["severity"] == "error");
      CHECK(f["object"] == "table");
      CHECK(f["group"] == "top");
      CHECK(f["material"] == "white");
    }
  }
  CHECK(bad == 12);
}

TEST_CASE("radwalk check: -q silences the warnings and keeps their count", "[cli][findings]") {
  const std::string scene = source("tests/data/zero_area.obj");
  const Run loud = run_loud("check " + scene);
  INFO(loud.out);
  CHECK(loud.exit_code == 0);
  CHECK(contains(loud.out, "radwalk: warning: "));
  CHECK(contains(loud.out, "degenerate face dropped"));
  const Run quiet = run("check " + scene);  // run() passes --quiet
  INFO(quiet.out);
  CHECK(quiet.exit_code == 0);
  CHECK_FALSE(contains(quiet.out, "radwalk: warning: "));
  CHECK(contains(quiet.out, "1 repair"));
  CHECK(contains(quiet.out, "warning(s) not shown (--quiet)"));
}


TEST_CASE("radwalk --set MATERIAL.Kd gives byte for byte the B of the edited MTL, and is recorded in the JSON",
          "[cli][overrides]") {
  const fs::path dir = scratch_dir("set_material");
  const fs::path edited = edited_cornell_box(dir, "Kd 0.5 0.4 0.3", false);
  const std::string common = " --max-edge 150 --rays 300 --seed 7";
  const std::string json = (dir / "set.json").string();
  const Run a = run("solve " + edited.string() + common + " --csv " + (dir / "edited.csv").string());
  const Run b = run("solve " + source("meshes/cornell_box.obj") + common + " --set white.Kd=0.5,0.4,0.3 --csv " +
                    (dir / "set.csv").string() + " --json " + json);
  INFO(a.out << b.out);
  REQUIRE(a.exit_code == 0);
  REQUIRE(b.exit_code == 0);
  // Equal but for the run id (the last column), which differs because the options and the inputs differ.
  const std::string edited_csv = csv_without_run_id(slurp(dir / "edited.csv")),
                    set_csv = csv_without_run_id(slurp(dir / "set.csv"));
  CHECK(!edited_csv.empty());
  CHECK(edited_csv == set_csv);
  const auto j = nlohmann::json::parse(slurp(json));
  REQUIRE(j["material_overrides"].size() == 1);
  CHECK(j["material_overrides"][0]["material"] == "white");
  CHECK(j["material_overrides"][0]["property"] == "Kd");
  CHECK(j["material_overrides"][0]["value"][1] == 0.4);
  CHECK(j["rho_scale"] == 1.0);
  // The unchanged scene differs (the override is not a no-op).
  run("solve " + source("meshes/cornell_box.obj") + common + " --csv " + (dir / "plain.csv").string());
  CHECK(slurp(dir / "plain.csv") != set_csv);
}

TEST_CASE("radwalk --rho-scale 0.5 equals every Kd halved in the MTL, a scale reaching rho 1 is refused",
          "[cli][overrides]") {
  const fs::path dir = scratch_dir("rho_scale");
  const fs::path edited = edited_cornell_box(dir, "", true);
  const std::string common = " --max-edge 150 --rays 300 --seed 3";
  const Run a = run("solve " + edited.string() + common + " --csv " + (dir / "edited.csv").string());
  const Run b = run("solve " + source("meshes/cornell_box.obj") + common + " --rho-scale 0.5 --csv " +
                    (dir / "scaled.csv").string());
  INFO(a.out << b.out);
  REQUIRE(a.exit_code == 0);
  REQUIRE(b.exit_code == 0);
  const std::string edited_csv = csv_without_run_id(slurp(dir / "edited.csv"));
  CHECK(!edited_csv.empty());
  CHECK(edited_csv == csv_without_run_id(slurp(dir / "scaled.csv")));
  const Run bright = run("check " + source("meshes/cornell_box.obj") + " --rho-scale 1.3");
  CHECK(bright.exit_code == 2);
  CHECK(contains(bright.out, "reaches 1"));
  const Run typo = run("solve " + source("meshes/cornell_box.obj") + " --set whte.Ke=3");
  CHECK(typo.exit_code == 2);
  CHECK(contains(typo.out, "did you mean 'white'"));
  const Run property = run("patch " + source("meshes/cornell_box.obj") + " -o " + (dir / "p.vtp").string() +
                           " --set light.Kf=3");
  CHECK(property.exit_code == 2);
  CHECK(contains(property.out, "did you mean"));
  const Run nan = run("pathtrace " + source("meshes/cornell_box.obj") + " --set light.Ke=nan --spp 2");
  CHECK(nan.exit_code == 2);
  CHECK(contains(nan.out, "not a finite number"));
}

TEST_CASE("radwalk solve: rays escaping a closed shell are a warning naming the patch and its group",
          "[cli][findings]") {
  const fs::path dir = scratch_dir("escaped");
  const std::string json = (dir / "escaped.json").string();
  // --orient none keeps the flipped wall (the default turns it in: below).
  const Run r = run_loud("solve " + source("tests/data/closed_cube_flipped_wall.obj") + " --orient none --rays 500 --json " +
                         json);
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  CHECK(contains(r.out, "500 of 3000 rays (16.7 %) escaped although the scene's faces form a closed shell"));
  CHECK(contains(r.out, "Most from patch 3 (input face 3 (object 'room', group 'outward', material 'white'))"));
  const auto j = nlohmann::json::parse(slurp(json));
  CHECK(j["closed_shell"] == true);
  REQUIRE(j["escaped_by_group"].size() == 1);
  CHECK(j["escaped_by_group"][0]["escaped"] == 500);
  // By default (--orient outward) the wall is turned into the room: nothing escapes, and the flip is a warning.
  const Run turned = run_loud("solve " + source("tests/data/closed_cube_flipped_wall.obj") + " --rays 500");
  CHECK(turned.exit_code == 0);
  CHECK_FALSE(contains(turned.out, "escaped although"));
  CHECK(contains(turned.out, "1 faces (area 1) flipped by --orient outward"));
  // The same cube with its wall facing in: closed, nothing escapes, no warning.
  const Run ok = run_loud("solve " + source("meshes/cube.obj") + " --rays 500");
  CHECK(ok.exit_code == 0);
  CHECK_FALSE(contains(ok.out, "escaped although"));
}
