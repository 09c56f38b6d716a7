// One- and two-sided surfaces on the command line (docs/two-sided.md): the MTL statement
// radwalk_two_sided, --two-sided, and what the outputs say about sides (the side column, back_patches).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "radwalk_runner.h"

namespace fs = std::filesystem;

namespace {

// The bundled unit cube (inward, the ceiling emits) with a thin panel across its middle, x = 0.5, as two quads
// of material `panel`; the MTL marks the panel two-sided when `two_sided_panel`.
fs::path write_panel_scene(const fs::path& dir, bool two_sided_panel) {
  std::ifstream cube(source("meshes/cube.obj"));
  std::stringstream obj;
  obj << cube.rdbuf();
  obj << "mtllib panel.mtl\nv 0.5 0.1 0.1\nv 0.5 0.1 0.9\nv 0.5 0.5 0.9\nv 0.5 0.5 0.1\nv 0.5 0.9 0.9\n"
         "v 0.5 0.9 0.1\nusemtl panel\nf 9 10 11 12\nf 12 11 13 14\n";
  std::ofstream(dir / "panel.obj") << obj.str();  // two libraries: cube.mtl (copied below) and panel.mtl
  std::ifstream cube_mtl(source("meshes/cube.mtl"));
  std::stringstream mtl;
  mtl << cube_mtl.rdbuf();
  std::ofstream(dir / "cube.mtl") << mtl.str();
  std::ofstream(dir / "panel.mtl") << "newmtl panel\nKd 0.6 0.6 0.6\n" << (two_sided_panel ? "radwalk_two_sided 1\n" : "");
  return dir / "panel.obj";
}

std::vector<std::string> header(const fs::path& csv) {
  std::ifstream in(csv);
  std::string line, cell;
  std::getline(in, line);
  std::vector<std::string> cells;
  std::stringstream s(line);
  while (std::getline(s, cell, ',')) cells.push_back(cell);
  return cells;
}

}  // namespace

TEST_CASE("radwalk: radwalk_two_sided and --two-sided give back patches, a side column and back_patches",
          "[cli][two-sided]") {
  const fs::path dir = scratch_dir("two_sided");
  struct Case {
    bool statement, flag;
    long patches, back;
    const char* open_shells;  // extra option
  };
  // 6 cube faces + 2 panel faces; the panel's 2 faces doubled by the statement, or by default (--open-shells
  // auto: the panel is an open shell inside the closed cube), all 8 by --two-sided; none with --open-shells
  // one-sided.
  for (const Case c : {Case{false, false, 8, 0, " --open-shells one-sided"}, Case{false, false, 10, 2, ""},
                       Case{true, false, 10, 2, ""}, Case{true, false, 10, 2, " --open-shells one-sided"},
                       Case{false, true, 16, 8, ""}}) {
    const fs::path obj = write_panel_scene(dir, c.statement);
    const fs::path csv = dir / "out.csv", json = dir / "out.json";
    const Run r = run("solve " + obj.string() + " --rays 2000 --csv " + csv.string() + " --json " + json.string() +
                      (c.flag ? " --two-sided" : "") + c.open_shells);
    INFO("statement " << c.statement << ", --two-sided " << c.flag << c.open_shells << ": " << r.out);
    REQUIRE(r.exit_code == 0);
    const nlohmann::json j = nlohmann::json::parse(std::ifstream(json));
    CHECK(j["patches"] == c.patches);
    CHECK(j.value("back_patches", 0L) == c.back);
    CHECK(j.contains("two_sided") == c.flag);
    const auto h = header(csv);
    REQUIRE(h.size() > 3);
    if (c.back == 0) {
      CHECK(h[2] == "area");  // one-sided: the layout of every one-sided scene, no side column
    } else {
      CHECK(h[2] == "side");
      std::ifstream in(csv);
      std::string line;
      std::getline(in, line);
      long backs = 0, rows = 0;
      while (std::getline(in, line)) {
        std::stringstream s(line);
        std::string patch, face, side;
        std::getline(s, patch, ',');
        std::getline(s, face, ',');
        std::getline(s, side, ',');
        // Back patches come after all front patches and keep their input face.
        if (side == "1") {
          ++backs;
          CHECK(rows >= c.patches - c.back);
          CHECK(std::stol(face) < 8);
        }
        ++rows;
      }
      CHECK(backs == c.back);
      CHECK(rows == c.patches);
    }
  }
  // The path tracer takes the same flag.
  const fs::path obj = write_panel_scene(dir, false);
  const Run pt = run("pathtrace " + obj.string() + " --two-sided --spp 8 --csv " + (dir / "pt.csv").string());
  INFO(pt.out);
  CHECK(pt.exit_code == 0);
  CHECK(header(dir / "pt.csv")[2] == "side");
}
