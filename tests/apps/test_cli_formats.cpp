// The scene formats end to end (mesh/read_scene.h): STL and glTF versions of a scene solve to the OBJ's areas and
// radiosity, a .vtp radwalk wrote reads back with its names, rho and E, `patch -o X.obj` of a two-sided scene reads
// back as the same patches, the CSV names each patch's object, group and material, and malformed or unsupported
// files are one-line refusals (exit 2).
#include <catch2/catch.hpp>

#include <algorithm>
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

namespace {

std::string text_of(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A 2 m room facing in with a 0.4 m cabinet standing on its floor (one-sided, facing out, with its bottom lying on
// the floor) and, with `panel`, a thin panel in the air modelled as two faces back to back (as exporters write
// thin parts): "NAME.obj" and its MTL in dir.
fs::path write_cabinet_room(const fs::path& dir, const std::string& name, bool panel) {
  std::ofstream(dir / (name + ".mtl")) << "newmtl floor\nKd 0.7 0.6 0.5\nnewmtl wall\nKd 0.5 0.5 0.5\n"
                                          "newmtl lamp\nKd 0 0 0\nKe 5 5 5\nnewmtl cab\nKd 0.3 0.2 0.1\n"
                                          "newmtl board\nKd 0.6 0.6 0.6\n";
  std::ofstream obj(dir / (name + ".obj"));
  obj << "mtllib " << name << ".mtl\n";
  int vertices = 0;
  // A box's six faces (bottom, top, then the sides), counter-clockwise seen from outside, or from inside.
  const auto box = [&](double x0, double x1, double y0, double y1, double z0, double z1, bool inward,
                       const std::vector<std::string>& materials) {
    const double c[8][3] = {{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0},
                            {x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}};
    for (const auto& p : c) obj << "v " << p[0] << " " << p[1] << " " << p[2] << "\n";
    const int f[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};
    for (int k = 0; k < 6; ++k) {
      obj << "usemtl " << materials[std::min<std::size_t>(static_cast<std::size_t>(k), materials.size() - 1)]
          << "\nf";
      for (int j = 0; j < 4; ++j) obj << " " << vertices + 1 + f[k][inward ? 3 - j : j];
      obj << "\n";
    }
    vertices += 8;
  };
  obj << "o room\n";
  box(0, 2, 0, 2, 0, 2, true, {"floor", "lamp", "wall"});
  obj << "o cabinet\n";
  box(0.5, 0.9, 0.5, 0.9, 0, 0.6, false, {"cab"});
  if (panel) {
    obj << "o panel\nusemtl board\nv 1.2 0.3 0.5\nv 1.8 0.3 0.5\nv 1.8 0.3 1.1\nv 1.2 0.3 1.1\n";
    const int v = vertices + 1;
    obj << "f " << v << " " << v + 1 << " " << v + 2 << " " << v + 3 << "\nf " << v << " " << v + 3 << " "
        << v + 2 << " " << v + 1 << "\n";
  }
  return dir / (name + ".obj");
}

}  // namespace

TEST_CASE("radwalk: a scene cut along its contacts reads back from its .vtp cell for cell, the floor under a "
          "cabinet and the cabinet's bottom two one-sided patches", "[cli][formats][contact]") {
  // With --contact-cut the floor piece under the cabinet and the cabinet's bottom lie on each other back to back
  // on the same corners (a contact pair). The .vtp names the pair (cell field contact_pair), so reading it back
  // gives the run's patches in the run's order with their own materials, where the duplicate-face repair made the
  // pair one two-sided face (the floor's material on both sides, its back patch moved to the end).
  const fs::path dir = scratch_dir("contact_round_trip");
  const std::vector<std::string> columns = {"area", "cx",    "cy",    "cz",  "nx",  "ny",  "nz",     "rho_r",
                                            "rho_g", "rho_b", "E_r", "E_g", "E_b", "object", "group", "material"};
  struct Scene {
    std::string file, options;
    std::size_t patches;
  };
  for (const Scene& s : {Scene{write_cabinet_room(dir, "cabinet", false).string(), " --max-edge 0.4", 0},
                         Scene{source("meshes/cornell_box.obj"), " --max-edge 100", 360}}) {
    INFO(s.file);
    const Run first = run("patch " + s.file + s.options + " --contact-cut -o " + (dir / "cut.vtp").string() +
                          " --csv " + (dir / "a.csv").string());
    INFO(first.out);
    REQUIRE(first.exit_code == 0);
    const Run again = run("patch " + (dir / "cut.vtp").string() + " -o " + (dir / "b.vtp").string() + " --csv " +
                          (dir / "b.csv").string() +
                          " --json " + (dir / "b.json").string());
    INFO(again.out);
    REQUIRE(again.exit_code == 0);
    const Table a = read_csv(dir / "a.csv"), b = read_csv(dir / "b.csv");
    if (s.patches > 0) REQUIRE(a.rows == s.patches);
    require_same_columns(a, b, columns);
    REQUIRE(text_of(dir / "b.json").find("duplicate face") == std::string::npos);
  }
  // The cabinet's room has its pair: the bottom (nz = -1) at z = 0 with the cabinet's material, the floor piece
  // under it (nz = 1) with the floor's.
  {
    const Run first = run("patch " + (dir / "cabinet.obj").string() + " --max-edge 0.4 --contact-cut -o " +
                          (dir / "cut.vtp").string() + " --csv " + (dir / "a.csv").string());
    REQUIRE(first.exit_code == 0);
    const Table a = read_csv(dir / "a.csv");
    std::size_t bottoms = 0;
    for (std::size_t i = 0; i < a.rows; ++i)
      bottoms += a.column.at("material")[i] == "cab" && std::stod(a.column.at("nz")[i]) == -1 &&
                 std::stod(a.column.at("cz")[i]) == 0;
    REQUIRE(bottoms == 1);
  }
  // A thin panel modelled as two faces back to back in an OBJ is still one two-sided face, with its warning, and
  // so is it in the .vtp read back (written as the front and back of one two-sided face).
  const fs::path panel = write_cabinet_room(dir, "panel", true);
  const Run obj = run("patch " + panel.string() + " --max-edge 0.4 --contact-cut -o " + (dir / "panel.vtp").string() +
                      " --csv " + (dir / "a.csv").string() + " --json " + (dir / "a.json").string());
  INFO(obj.out);
  REQUIRE(obj.exit_code == 0);
  REQUIRE(text_of(dir / "a.json").find("back-to-back faces made two-sided") != std::string::npos);
  const Run vtp = run("patch " + (dir / "panel.vtp").string() + " -o " + (dir / "b.vtp").string() + " --csv " +
                      (dir / "b.csv").string());
  INFO(vtp.out);
  REQUIRE(vtp.exit_code == 0);
  const Table a = read_csv(dir / "a.csv"), b = read_csv(dir / "b.csv");
  REQUIRE(a.column.count("side") == 1);
  require_same_columns(a, b, columns);
  require_same_columns(a, b, {"side"});
  fs::remove_all(dir);
}

TEST_CASE("radwalk: a scene cut along its contacts reads back from its .obj face for face, the floor under a "
          "cabinet and the cabinet's bottom two one-sided patches", "[cli][formats][contact]") {
  // As the .vtp above: radwalk's .obj names the pair ("# radwalk_contact_pair A B" after the faces), so reading it
  // back gives the run's patches in the run's order with their own materials, where the duplicate-face repair made
  // the pair one two-sided face.
  const fs::path dir = scratch_dir("contact_round_trip_obj");
  const std::vector<std::string> columns = {"area", "cx",    "cy",    "cz",  "nx",  "ny",  "nz",     "rho_r",
                                            "rho_g", "rho_b", "E_r", "E_g", "E_b", "object", "group", "material"};
  struct Scene {
    std::string file, options;
    std::size_t patches;
  };
  // The Cornell box's blocks have no bottom, so no pair, but the cut pieces under them close the blocks' shells
  // in the written file: they read back facing up as written (the file's "# radwalk_as_written" line).
  for (const Scene& s : {Scene{write_cabinet_room(dir, "cabinet", false).string(), " --max-edge 0.4", 0},
                         Scene{source("meshes/cornell_box.obj"), " --max-edge 100", 360}}) {
    INFO(s.file);
    const Run first = run("patch " + s.file + s.options + " --contact-cut -o " + (dir / "cut.obj").string() +
                          " --csv " + (dir / "a.csv").string());
    INFO(first.out);
    REQUIRE(first.exit_code == 0);
    if (s.patches == 0) REQUIRE(text_of(dir / "cut.obj").find("\n# radwalk_contact_pair ") != std::string::npos);
    const Run again = run("patch " + (dir / "cut.obj").string() + " -o " + (dir / "b.obj").string() + " --csv " +
                          (dir / "b.csv").string() + " --json " + (dir / "b.json").string());
    INFO(again.out);
    REQUIRE(again.exit_code == 0);
    const Table a = read_csv(dir / "a.csv"), b = read_csv(dir / "b.csv");
    if (s.patches > 0) REQUIRE(a.rows == s.patches);
    require_same_columns(a, b, columns);
    REQUIRE(text_of(dir / "b.json").find("duplicate face") == std::string::npos);
    REQUIRE(text_of(dir / "b.json").find("made two-sided") == std::string::npos);
    REQUIRE(text_of(dir / "b.json").find("faces flipped") == std::string::npos);
  }
  fs::remove_all(dir);
}

TEST_CASE("radwalk: patch -o X.obj reads back facing as written with the solution of its .vtp", "[cli][formats]") {
  // The Cornell box cut along the blocks' footprints (the default): the floor pieces under the bottomless blocks
  // face up, into the blocks, whose shells they close. The .obj says its faces are oriented as written, so solving
  // it gives the .vtp's patches (count, centroids, normals) and, with the same seed, its solution digit for digit.
  // Control: --orient outward given orients the file again (with a note) and turns those pieces to face down.
  const fs::path dir = scratch_dir("obj_as_written");
  const std::string cornell = source("meshes/cornell_box.obj");
  for (const std::string out : {"cut.obj", "cut.vtp"}) {
    const Run r = run("patch " + cornell + " --max-edge 100 -o " + (dir / out).string() + " --csv " +
                      (dir / (out + ".csv")).string());
    INFO(r.out);
    REQUIRE(r.exit_code == 0);
  }
  const Table written = read_csv(dir / "cut.obj.csv");
  REQUIRE(written.rows == 360);
  const std::string solve = " --rays 500 --seed 5 --csv ";
  const Run from_obj = run("solve " + (dir / "cut.obj").string() + solve + (dir / "obj.csv").string() + " --json " +
                           (dir / "obj.json").string());
  INFO(from_obj.out);
  REQUIRE(from_obj.exit_code == 0);
  const Run from_vtp = run("solve " + (dir / "cut.vtp").string() + solve + (dir / "vtp.csv").string());
  INFO(from_vtp.out);
  REQUIRE(from_vtp.exit_code == 0);
  const Table obj = read_csv(dir / "obj.csv"), vtp = read_csv(dir / "vtp.csv");
  REQUIRE(obj.rows == 360);
  require_same_columns(written, obj, {"area", "cx", "cy", "cz", "nx", "ny", "nz"});
  require_same_columns(vtp, obj, kSolution);
  REQUIRE(text_of(dir / "obj.json").find("faces flipped") == std::string::npos);

  const Run again = run("patch " + (dir / "cut.obj").string() + " --orient outward -o " + (dir / "again.vtp").string() +
                        " --csv " + (dir / "again.csv").string() + " --json " + (dir / "again.json").string());
  INFO(again.out);
  REQUIRE(again.exit_code == 0);
  REQUIRE(text_of(dir / "again.json").find("faces as written oriented again") != std::string::npos);
  REQUIRE(text_of(dir / "again.json").find("faces flipped") != std::string::npos);
  const Table turned = read_csv(dir / "again.csv");
  REQUIRE(turned.rows == 360);
  std::size_t down = 0;
  for (std::size_t i = 0; i < turned.rows; ++i)
    down += turned.column.at("nz")[i] != written.column.at("nz")[i] && std::stod(turned.column.at("nz")[i]) < 0;
  REQUIRE(down > 0);
  fs::remove_all(dir);
}
