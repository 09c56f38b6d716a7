// Every finding at once: validation collects every refusal, repair, warning and note of a scene,
// grouped by kind, before it refuses; T-junctions named at the T point; bent quads with an ambiguous area split;
// material overrides (--set, --rho-scale) act like the edited MTL.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "core/error.h"
#include "mesh/edge_table.h"
#include "mesh/finding.h"
#include "mesh/material_override.h"
#include "mesh/read_obj.h"
#include "mesh/read_scene.h"
#include "mesh/t_junctions.h"
#include "mesh/validate.h"

using namespace radwalk;

namespace {

std::string data(const std::string& name) { return std::string(RADWALK_SOURCE_DIR) + "/tests/data/" + name; }
bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

long count_kind(const std::vector<Finding>& findings, const std::string& kind) {
  return static_cast<long>(std::count_if(findings.begin(), findings.end(), [&](const Finding& f) { return f.kind == kind; }));
}

const Finding* first_of(const std::vector<Finding>& findings, const std::string& kind) {
  for (const Finding& f : findings)
    if (f.kind == kind) return &f;
  return nullptr;
}

// The findings of loading `name` and the refusal's message ("" if accepted).
std::pair<std::vector<Finding>, std::string> findings_of(const std::string& name, bool strict = false) {
  ReadOptions options;
  options.strict = strict;
  try {
    const Mesh mesh = load_scene(data(name), options);
    return {mesh.findings, ""};
  } catch (const MeshRefused& e) {
    return {e.findings(), e.what()};
  }
}

Mesh mesh_of(std::vector<Vec3> vertices, std::vector<std::array<std::int32_t, 4>> faces) {
  Mesh mesh;
  mesh.path = "test.obj";
  mesh.vertices = std::move(vertices);
  mesh.faces = std::move(faces);
  Material light;
  light.name = "light";
  light.Kd = Rgb::Constant(0.5);
  light.Ke = Rgb::Ones();
  mesh.materials = {light};
  mesh.face_material.assign(mesh.faces.size(), 0);
  return mesh;
}

}  // namespace

TEST_CASE("a file with several different defects reports all of them in one run, grouped, with counts",
          "[mesh][findings]") {
  const auto [findings, message] = findings_of("many_defects.obj");
  REQUIRE_FALSE(message.empty());
  // Errors of every kind, with their faces, lines, object, group and material.
  CHECK(count_kind(findings, "bad vertex index") == 12);
  CHECK(count_kind(findings, "non-finite coordinate") == 1);
  // Repaired since exporters write them: the triangle 5 5 6 (no area, dropped), a copy of face 0 (dropped), the
  // face of the unknown material (given the default) and its copy of material 'bright' (dropped).
  CHECK(count_kind(findings, "face without area dropped") == 1);
  CHECK(count_kind(findings, "duplicate face dropped") == 2);
  CHECK(count_kind(findings, "self-intersecting quad") == 1);
  CHECK(count_kind(findings, "unknown material") == 0);
  CHECK(count_kind(findings, "unknown material given the default") == 1);
  CHECK(count_kind(findings, "reflectance out of range") == 1);
  // Repairs found in the same run.
  CHECK(count_kind(findings, "polygon triangulated") == 1);
  CHECK(count_kind(findings, "zero-area face dropped") == 1);
  const Finding* bad = first_of(findings, "bad vertex index");
  REQUIRE(bad != nullptr);
  CHECK(bad->severity == Severity::error);
  CHECK(bad->face == 1);
  CHECK(bad->line == 32);
  CHECK(bad->object == "table");
  CHECK(bad->group == "top");
  CHECK(bad->material == "white");
  const Finding* unknown = first_of(findings, "unknown material given the default");
  REQUIRE(unknown != nullptr);
  CHECK(unknown->severity == Severity::repair);
  CHECK(unknown->face == 19);
  CHECK(unknown->line == 50);  // the usemtl line
  CHECK(unknown->material == "no_such_material");
  const Finding* nan = first_of(findings, "non-finite coordinate");
  REQUIRE(nan != nullptr);
  CHECK(nan->face == 13);
  // One line: the first error and the count of the others.
  CHECK(message.find('\n') == std::string::npos);
  CHECK(contains(message, "many_defects.obj:32: face 1: bad vertex index"));
  CHECK(contains(message, "and 14 more"));
  CHECK(contains(message, "12 bad vertex index"));

  // Grouped lines: 10 of the 12 bad indices, then "2 more (12 in all)"; kinds in order of first appearance.
  const std::vector<std::string> lines = grouped_lines(findings, {Severity::error}, 10);
  REQUIRE(lines.size() == 11 + 1 + 1 + 1);
  CHECK(contains(lines[0], "many_defects.obj:32: face 1: bad vertex index"));
  CHECK(contains(lines[0], "(object 'table', group 'top', material 'white')"));
  CHECK(contains(lines[10], "bad vertex index: 2 more (12 in all)"));
  CHECK(count_by_kind(findings, Severity::error) ==
        "15 errors (12 bad vertex index, 1 non-finite coordinate, 1 self-intersecting quad, "
        "1 reflectance out of range)");
}

TEST_CASE("with --strict the repairs of the same file are refusals too, found in the same run", "[mesh][findings]") {
  const auto [findings, message] = findings_of("many_defects.obj", true);
  REQUIRE_FALSE(message.empty());
  CHECK(count_kind(findings, "polygon of more than 4 corners") == 1);
  CHECK(count_kind(findings, "degenerate face") == 1);
  CHECK(count_kind(findings, "bad vertex index") == 12);
  CHECK(count_kind(findings, "polygon triangulated") == 0);
}

TEST_CASE("a face without material: the warning names the default once", "[mesh][findings]") {
  const Mesh mesh = load_scene(data("no_material.obj"));
  const Finding* f = first_of(mesh.findings, "face without material");
  REQUIRE(f != nullptr);
  CHECK(f->severity == Severity::repair);
  CHECK(f->material.empty());
  const std::string line = finding_line(*f);
  INFO(line);
  // Before: "face without material: given 'radwalk_default' (...) (material 'radwalk_default')".
  CHECK(line.find("radwalk_default") == line.rfind("radwalk_default"));
}

TEST_CASE("T-junctions are named at the T point, as a note, and are not non-manifold vertices", "[mesh][findings]") {
  // A square 0-1-2-3 beside two small ones that meet at 6 = (1, 0.5), inside the square's edge 1 - 2:
  //   3 ---- 2 ---- 7
  //   |      6 ---- 5     the T point is index 6 (file vertex 7), on the edge of indices 1 - 2 (file vertices 2 - 3)
  //   0 ---- 1 ---- 4
  Mesh mesh = mesh_of({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 0.5, 0}, {1, 0.5, 0}, {2, 1, 0}},
                      {{0, 1, 2, 3}, {1, 4, 5, 6}, {6, 5, 7, 2}});
  validate_mesh(mesh);
  REQUIRE(count_kind(mesh.findings, "T-junction") == 1);
  const Finding* t = first_of(mesh.findings, "T-junction");
  CHECK(t->severity == Severity::note);
  CHECK(t->face == 0);
  CHECK(contains(t->message, "vertex 7 lies on this face's edge"));
  CHECK(contains(t->message, "harmless for the constant-radiosity solve"));
  // Before, file vertices 2 and 3 were reported as non-manifold (two fans each, joined only across the junction).
  CHECK(count_kind(mesh.findings, "non-manifold vertex") == 0);
}

TEST_CASE("closed shells: a closed room around open objects is closed, and outward faces on its planes are not the room",
          "[mesh][findings]") {
  // A closed room with a table top modelled as one sheet was not a closed shell, so rays escaping it
  // through furniture bottoms lying on the floor were not reported.
  std::vector<Vec3> v = {{0, 0, 0}, {4, 0, 0}, {4, 3, 0}, {0, 3, 0}, {0, 0, 4}, {4, 0, 4}, {4, 3, 4}, {0, 3, 4}};
  // the room, facing in (the reversed windings of a closed box facing out)
  std::vector<std::array<std::int32_t, 4>> room = {{1, 2, 3, 0}, {7, 6, 5, 4}, {4, 5, 1, 0},
                                                   {5, 6, 2, 1}, {6, 7, 3, 2}, {7, 4, 0, 3}};
  // an open sheet in the room (a table top) and a box bottom on the floor facing down (out of the room)
  for (const Vec3& p : {Vec3(1, 1, 1), Vec3(2, 1, 1), Vec3(2, 1, 2), Vec3(1, 1, 2), Vec3(3, 0, 3), Vec3(3.5, 0, 3),
                        Vec3(3.5, 0, 3.5), Vec3(3, 0, 3.5)})
    v.push_back(p);
  auto faces = room;
  faces.push_back({8, 11, 10, 9});    // the sheet, facing up
  faces.push_back({12, 13, 14, 15});  // the bottom, facing down: on the floor's plane, not part of the room
  const Mesh scene = mesh_of(v, faces);
  CHECK(enclosure_faces(scene) == std::vector<std::size_t>{0, 1, 2, 3, 4, 5});
  CHECK_FALSE(find_t_junctions(scene, build_edge_table(scene)).closed());  // the sheet has open edges
  CHECK(is_closed_shell(scene));
  // Without the ceiling the room is open.
  auto open = faces;
  open.erase(open.begin() + 4);
  CHECK_FALSE(is_closed_shell(mesh_of(v, open)));
  // A box facing out (a closed object, seen from outside) is closed on its own; with an open sheet beside it,
  // its faces face out of its bounding box: no enclosure, not closed.
  auto outward = faces;
  for (std::size_t f = 0; f < 6; ++f) std::reverse(outward[f].begin(), outward[f].end());
  const Mesh object = mesh_of(v, outward);
  CHECK(enclosure_faces(object).empty());
  CHECK_FALSE(is_closed_shell(object));
}

TEST_CASE("closed shells: a cube is closed, with or without a T-junction, an open box is not", "[mesh][findings]") {
  const std::vector<Vec3> cube = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const std::vector<std::array<std::int32_t, 4>> sides = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                                          {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  CHECK(is_closed_shell(mesh_of(cube, sides)));
  auto open = sides;
  open.pop_back();
  CHECK_FALSE(is_closed_shell(mesh_of(cube, open)));
  // The top split in two along x = 0.5 with the T points on the edges 4-5 and 7-6 of the sides.
  auto points = cube;
  points.push_back({0.5, 0, 1});  // 8
  points.push_back({0.5, 1, 1});  // 9
  auto split = sides;
  split[1] = {4, 8, 9, 7};
  split.push_back({8, 5, 6, 9});
  const Mesh t_cube = mesh_of(points, split);
  const BoundaryCover cover = find_t_junctions(t_cube, build_edge_table(t_cube));
  CHECK(cover.t_junctions.size() == 2);
  CHECK(cover.closed());
}

TEST_CASE("a bent quad whose area is ambiguous is split along the better diagonal, --strict refuses it",
          "[mesh][findings]") {
  // The fuzz finding: 0.74 % of its width off its plane, but triangulations of 34435.5 and 34422.1 and a vector
  // area of 33988.3 (its patches added up to 34057).
  const std::vector<Vec3> bent = {{0, 1, 0}, {1, 0, 0}, {343, 548.8, 332}, {343, 548.8, 227}};
  Mesh mesh = mesh_of(bent, {{0, 1, 2, 3}});
  validate_mesh(mesh);
  REQUIRE(mesh.face_count() == 2);
  CHECK_FALSE(mesh.is_quad(0));
  CHECK(mesh.face_source[0] == 0);
  CHECK(mesh.face_source[1] == 0);
  const Finding* f = first_of(mesh.findings, "area-ambiguous quad split");
  REQUIRE(f != nullptr);
  CHECK(f->severity == Severity::repair);
  Mesh strict = mesh_of(bent, {{0, 1, 2, 3}});
  ValidationTolerances tol;
  tol.strict = true;
  CHECK_THROWS_WITH(validate_mesh(strict, tol), Catch::Contains("area-ambiguous") || Catch::Contains("bent quad"));
  // A planar square is not touched.
  Mesh square = mesh_of({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2, 3}});
  validate_mesh(square);
  CHECK(square.face_count() == 1);
}

TEST_CASE("the bundled Cornell box has no area-ambiguous quad and stays unsplit", "[mesh][findings]") {
  const Mesh box = load_scene(std::string(RADWALK_SOURCE_DIR) + "/meshes/cornell_box.obj");
  CHECK(box.face_count() == 37);
  // Only notes: the open box and its open blocks (open shells).
  for (const Finding& f : box.findings) {
    INFO(f.kind << ": " << f.message);
    CHECK(f.severity == Severity::note);
    CHECK(f.kind == "open shell");
  }
}

TEST_CASE("material overrides: --set and --rho-scale act like the edited MTL", "[mesh][overrides]") {
  const MaterialOverride kd = parse_material_override("white.Kd=0.2,0.3,0.4");
  CHECK(kd.material == "white");
  CHECK(kd.property == "Kd");
  CHECK((kd.value == Rgb(0.2, 0.3, 0.4)).all());
  const MaterialOverride grey = parse_material_override("my.light.Ke=12");
  CHECK(grey.material == "my.light");
  CHECK((grey.value == Rgb::Constant(12)).all());
  CHECK_THROWS_WITH(parse_material_override("white.Kb=0.5"), Catch::Contains("did you mean 'Kd'"));
  CHECK_THROWS_WITH(parse_material_override("white.Kd=1,0,0"), Catch::Contains("[0, 1)"));
  CHECK_THROWS_WITH(parse_material_override("white.Kd=nan"), Catch::Contains("not a finite number"));
  CHECK_THROWS_WITH(parse_material_override("white.Kd=0.1,0.2"), Catch::Contains("1 or 3 numbers"));
  CHECK_THROWS_WITH(parse_material_override("white.Ke=-1"), Catch::Contains("out of range"));
  CHECK_THROWS_WITH(parse_material_override("whiteKd=1"), Catch::Contains("no material name"));

  const Mesh mesh = read_scene(std::string(RADWALK_SOURCE_DIR) + "/meshes/cornell_box.obj");
  Mesh typo = mesh;
  CHECK_THROWS_WITH(apply_material_overrides(typo, {parse_material_override("whte.Kd=0.5")}),
                    Catch::Contains("no material 'whte'") && Catch::Contains("did you mean 'white'"));
  Mesh scaled = mesh;
  apply_material_overrides(scaled, {parse_material_override("white.Kd=0.5,0.25,0.125")}, 0.5);
  for (const Material& m : scaled.materials)
    if (m.name == "white") CHECK((m.Kd == Rgb(0.25, 0.125, 0.0625)).all());
  Mesh too_bright = mesh;  // white has Kd 0.73 or so: twice that reaches 1
  CHECK_THROWS_WITH(apply_material_overrides(too_bright, {}, 2.0), Catch::Contains("reaches 1"));
}

TEST_CASE("usemtl naming a material no library defines: its faces get the default material under that name, one "
          "warning with the count, --strict refuses",
          "[mesh][findings]") {
  const std::string mtl = "newmtl wall\nKd 0.3 0.3 0.3\nnewmtl light\nKd 0 0 0\nKe 1 1 1\n";
  const MtlSource one_library = {[](const std::string& p) { return p.size() >= 5 && p.compare(p.size() - 5, 5, "m.mtl") == 0; },
                                 [&](const std::string&) { return mtl; }};
  const std::string obj =
      "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"  // lines 1-9
      "o shelf\ng board\nusemtl oak\nf 1 2 3\nf 1 3 4\n"                                        // lines 10-14
      "usemtl light\nf 8 7 6 5\n"                                                                  // lines 15-16
      "usemtl oak\nf 1 2 6 5\n";                                                                   // lines 17-18
  Mesh mesh = read_obj_text("shelf.obj", obj, one_library);
  std::size_t warnings = 0;
  for (const Finding& f : mesh.findings) {
    CHECK(f.severity != Severity::error);
    if (f.kind != "unknown material given the default") continue;
    ++warnings;
    CHECK(f.severity == Severity::repair);
    CHECK(finding_line(f) ==
          "shelf.obj:12: face 0: unknown material 'oak' (usemtl at line 12: not in m.mtl): its 3 faces get the "
          "default material (rho 0.5, no emission) under that name; --set 'oak.Kd=r,g,b' sets it (--strict refuses "
          "it) (object 'shelf', group 'board', material 'oak')");
  }
  CHECK(warnings == 1);
  REQUIRE(mesh.face_count() == 4);
  for (std::size_t f : {0, 1, 3}) {
    const Material& m = mesh.materials[static_cast<std::size_t>(mesh.face_material[f])];
    CHECK(m.name == "oak");
    CHECK((m.Kd == 0.5).all());
    CHECK((m.Ke == 0).all());
  }
  REQUIRE_NOTHROW(validate_mesh(mesh));
  // --strict: each face is refused as before.
  ReadOptions strict;
  strict.strict = true;
  Mesh refused = read_obj_text("shelf.obj", obj, one_library, strict);
  std::size_t errors = 0;
  for (const Finding& f : refused.findings) errors += f.kind == "unknown material" && f.severity == Severity::error;
  CHECK(errors == 3);
  ValidationTolerances strict_tol;
  strict_tol.strict = true;
  CHECK_THROWS_WITH(validate_mesh(refused, strict_tol), Catch::StartsWith("shelf.obj:13: face 0: unknown material 'oak'"));
}
