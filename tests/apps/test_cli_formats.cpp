// The scene formats end to end (mesh/read_scene.h): STL and glTF versions of a scene solve to the OBJ's areas and
// radiosity, a .vtp radwalk wrote reads back with its names, rho and E, `patch -o X.obj` of a two-sided scene reads
// back as the same patches, the CSV names each patch's object, group and material, and malformed or unsupported
// files are one-line refusals (exit 2).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "radwalk_runner.h"
#include "support/scene_formats.h"

namespace fs = std::filesystem;

namespace {

// A CSV file as columns by header name (cells as written; the test scenes' names hold no comma).
struct Table {
  std::vector<std::string> header;
  std::map<std::string, std::vector<std::string>> column;
  std::size_t rows = 0;
};

Table read_csv(const fs::path& path) {
  std::ifstream in(path);
  REQUIRE(in);
  Table t;
  std::string line;
  std::getline(in, line);
  std::stringstream h(line);
  for (std::string cell; std::getline(h, cell, ',');) t.header.push_back(cell);
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    REQUIRE(cells.size() == t.header.size());
    for (std::size_t k = 0; k < cells.size(); ++k) t.column[t.header[k]].push_back(cells[k]);
    ++t.rows;
  }
  return t;
}

void require_same_columns(const Table& a, const Table& b, const std::vector<std::string>& columns) {
  REQUIRE(a.rows == b.rows);
  for (const std::string& c : columns) {
    INFO("column " << c);
    REQUIRE(a.column.count(c) == 1);
    REQUIRE(b.column.count(c) == 1);
    REQUIRE(a.column.at(c) == b.column.at(c));
  }
}

const std::vector<std::string> kSolution = {"area", "cx", "cy", "cz", "nx", "ny", "nz", "rho_r", "rho_g", "rho_b",
                                            "E_r", "E_g", "E_b", "B_r", "B_g", "B_b"};

}  // namespace

TEST_CASE("radwalk: STL and glTF versions of a scene give the OBJ's areas and radiosity", "[cli][formats]") {
  const fs::path dir = scratch_dir("formats");
  const radwalk::test::TriScene scene = radwalk::test::box_with_panel();
  radwalk::test::write_all_formats(scene, dir);
  // Same patches in the same order and the same seed: the same rays, so the same F and B, digit for digit.
  const std::string solve = " --rays 3000 --seed 7 --solver direct --csv ";
  const Run obj = run("solve " + (dir / "scene.obj").string() + solve + (dir / "obj.csv").string());
  REQUIRE(obj.exit_code == 0);
  const Table reference = read_csv(dir / "obj.csv");
  REQUIRE(reference.rows == 16);  // 14 triangles and the back patches of the panel (an open shell in a closed room)
  for (const std::string file : {"scene_ascii.stl", "scene.gltf", "scene.glb"}) {
    INFO(file);
    const bool stl = file.find(".stl") != std::string::npos;
    const Run r = run("solve " + (dir / file).string() + (stl ? radwalk::test::set_options(scene) : "") + solve +
                      (dir / "other.csv").string());
    INFO(r.out);
    REQUIRE(r.exit_code == 0);
    const Table other = read_csv(dir / "other.csv");
    require_same_columns(reference, other, kSolution);
    // Each STL solid and glTF mesh is the group (and its material) of the OBJ's `g` of the same name.
    require_same_columns(reference, other, {"group", "material"});
  }
  // Binary STL: one solid, so one material; the same patch areas and corners.
  const Run bin = run("patch " + (dir / "scene_binary.stl").string() + " --set scene_binary.Kd=0.5 -o " +
                      (dir / "bin.vtp").string() + " --csv " + (dir / "bin.csv").string());
  INFO(bin.out);
  REQUIRE(bin.exit_code == 0);
  require_same_columns(reference, read_csv(dir / "bin.csv"), {"area", "cx", "cy", "cz", "nx", "ny", "nz"});
  REQUIRE(read_csv(dir / "bin.csv").column.at("group").front() == "scene_binary");
  fs::remove_all(dir);
}

TEST_CASE("radwalk: a .vtp radwalk wrote reads back with its names, rho, E and patches", "[cli][formats]") {
  const fs::path dir = scratch_dir("vtp_round_trip");
  const radwalk::test::TriScene scene = radwalk::test::box_with_panel();
  radwalk::test::write_obj(scene, dir, "scene");
  const std::string solve = " --rays 2000 --seed 3 --max-edge 1.5 --csv ";
  const Run first = run("solve " + (dir / "scene.obj").string() + solve + (dir / "a.csv").string() + " -o " +
                        (dir / "a.vtp").string());
  INFO(first.out);
  REQUIRE(first.exit_code == 0);
  const Run again = run("solve " + (dir / "a.vtp").string() + solve + (dir / "b.csv").string());
  INFO(again.out);
  REQUIRE(again.exit_code == 0);
  const Table a = read_csv(dir / "a.csv"), b = read_csv(dir / "b.csv");
  REQUIRE(a.rows > 14);
  require_same_columns(a, b, kSolution);
  require_same_columns(a, b, {"object", "group", "material"});
  fs::remove_all(dir);
}

TEST_CASE("radwalk: patch -o X.obj of a two-sided scene reads back as the same patches", "[cli][formats][two-sided]") {
  const fs::path dir = scratch_dir("obj_round_trip");
  const radwalk::test::TriScene scene = radwalk::test::box_with_panel();
  radwalk::test::write_obj(scene, dir, "scene");
  std::ofstream(dir / "scene.mtl", std::ios::app) << "radwalk_two_sided 1\n";  // the last block: "white"
  std::ofstream(dir / "scene.obj", std::ios::app) << "v 1 1 2\nv 3 1 2\nv 3 3 2\no lamp\ng bulb\nusemtl panel\nf 29 30 31\n";
  const Run first = run("patch " + (dir / "scene.obj").string() + " --max-edge 2 -o " + (dir / "p.obj").string() +
                        " --csv " + (dir / "a.csv").string());
  INFO(first.out);
  REQUIRE(first.exit_code == 0);
  const Run again = run("patch " + (dir / "p.obj").string() + " --max-edge 2 -o " + (dir / "q.obj").string() +
                        " --csv " + (dir / "b.csv").string());
  INFO(again.out);
  REQUIRE(again.exit_code == 0);
  const Table a = read_csv(dir / "a.csv"), b = read_csv(dir / "b.csv");
  REQUIRE(a.column.count("side") == 1);
  std::size_t backs = 0;
  for (const std::string& s : a.column.at("side")) backs += s == "1";
  REQUIRE(backs > 0);
  require_same_columns(a, b, {"patch", "side", "area", "cx", "cy", "cz", "nx", "ny", "nz", "rho_r", "rho_g",
                              "rho_b", "E_r", "E_g", "E_b", "object", "group", "material"});
  // The names: the extra face is object 'lamp', group 'bulb'; the walls are in groups of their material.
  std::size_t bulbs = 0;
  for (std::size_t i = 0; i < a.rows; ++i)
    if (a.column.at("group")[i] == "bulb") {
      REQUIRE(a.column.at("object")[i] == "lamp");
      REQUIRE(a.column.at("material")[i] == "panel");
      ++bulbs;
    }
  REQUIRE(bulbs > 0);
  REQUIRE(a.column.at("group").front() == "white");
  fs::remove_all(dir);
}

TEST_CASE("radwalk: malformed and unsupported scene files are one-line refusals", "[cli][formats]") {
  const fs::path dir = scratch_dir("format_refusals");
  const radwalk::test::TriScene scene = radwalk::test::box_with_panel();
  radwalk::test::write_all_formats(scene, dir);
  struct Case {
    std::string file, bytes, words;
  };
  const std::string glb = [&] {
    std::ifstream in(dir / "scene.glb", std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }();
  const std::vector<Case> cases = {
      {"scene_ascii.stl", "", "--set 'white.Kd=r,g,b'"},  // no materials: --set is named
      {"cut.glb", glb.substr(0, glb.size() / 2), "GLB header: declares"},
      {"cut.stl", radwalk::test::binary_stl(scene).substr(0, 300), "binary STL declares 14 triangles"},
      {"model.dae", "<COLLADA/>", "assimp export"},
      {"model.fbx", "x", "Blender"},
  };
  for (const Case& c : cases) {
    INFO(c.file);
    if (!c.bytes.empty()) radwalk::test::write_file(dir / c.file, c.bytes);
    const Run r = run("check " + (dir / c.file).string());
    INFO(r.out);
    REQUIRE(r.exit_code == 2);
    REQUIRE(r.out.find(c.words) != std::string::npos);
    // The refusal is one line naming the file.
    const std::size_t at = r.out.find(c.words);
    const std::size_t start = r.out.rfind('\n', at) + 1;
    REQUIRE(r.out.substr(start, at - start).find((dir / c.file).string()) != std::string::npos);
  }
  fs::remove_all(dir);
}
