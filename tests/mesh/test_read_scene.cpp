// Reading scenes: the bundled meshes, exact material values, face order and lines, the PLY path.
#include <catch2/catch.hpp>

#include <fstream>
#include <string>

#include "core/error.h"
#include "mesh/face_geometry.h"
#include "mesh/read_scene.h"
#include "mesh/validate.h"

using namespace radwalk;

namespace {

std::string bundled(const std::string& name) { return std::string(RADWALK_SOURCE_DIR) + "/meshes/" + name; }
std::string data(const std::string& name) { return std::string(RADWALK_SOURCE_DIR) + "/tests/data/" + name; }

// Lines of the `f` statements of an OBJ file, found independently of the reader.
std::vector<long> face_lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<long> lines;
  long n = 0;
  for (std::string l; std::getline(in, l);) {
    ++n;
    if (l.rfind("f ", 0) == 0) lines.push_back(n);
  }
  return lines;
}

double area_of(const Mesh& mesh) {
  double a = 0;
  for (std::size_t f = 0; f < mesh.face_count(); ++f) a += face_area(mesh, f);
  return a;
}

double quad_area(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return 0.5 * ((b - a).cross(c - a).norm() + (c - a).cross(d - a).norm());
}

void print_warnings(const Mesh& mesh) {
  for (const auto& w : mesh.warnings) UNSCOPED_INFO("warning: " << w);
}

}  // namespace

TEST_CASE("bundled unit scenes load clean, with their documented faces and materials", "[mesh][read]") {
  struct Case {
    const char* file;
    std::size_t faces;
    double area;
  };
  for (const Case c : {Case{"cube.obj", 6, 6.0}, Case{"furnace.obj", 6, 6.0}, Case{"parallel_squares.obj", 2, 2.0},
                       Case{"perpendicular_squares.obj", 2, 2.0}}) {
    INFO(c.file);
    Mesh mesh = load_scene(bundled(c.file));
    print_warnings(mesh);
    CHECK(mesh.warnings.empty());
    CHECK(mesh.face_count() == c.faces);
    CHECK(area_of(mesh) == c.area);  // unit squares: exact in floating point
    CHECK(mesh.face_line == face_lines(bundled(c.file)));
  }
  const Mesh cube = load_scene(bundled("cube.obj"));
  for (std::size_t f = 0; f < 6; ++f) {
    const Material& m = cube.materials[static_cast<std::size_t>(cube.face_material[f])];
    INFO("face " << f << " material " << m.name << " Kd " << m.Kd.transpose() << " Ke " << m.Ke.transpose());
    CHECK((m.Kd == 0.5).all());
    CHECK((m.Ke == (f == 1 ? 1.0 : 0.0)).all());  // only the ceiling y = 1 emits
    // Normals point into the unit cube: towards its centre.
    const Vec3 n = face_vector_area(cube, f);
    const Vec3 corner = cube.vertices[static_cast<std::size_t>(cube.faces[f][0])];
    CHECK(n.dot(Vec3(0.5, 0.5, 0.5) - corner) > 0);
  }
}

TEST_CASE("the Cornell box checks clean and matches the Cornell data page", "[mesh][read][cornell]") {
  const Mesh mesh = load_scene(bundled("cornell_box.obj"));
  print_warnings(mesh);
  CHECK(mesh.warnings.empty());
  REQUIRE(mesh.face_count() == 37);
  CHECK(mesh.face_line == face_lines(bundled("cornell_box.obj")));

  // Materials: Cardenas and McGuire's CornellBox-Original values, read exactly.
  auto material = [&](std::size_t f) -> const Material& {
    return mesh.materials[static_cast<std::size_t>(mesh.face_material[f])];
  };
  const Material& white = material(0);
  const Material& light = material(9);
  CHECK(white.name == "white");
  CHECK(white.Kd[0] == 0.725);
  CHECK(white.Kd[1] == 0.71);
  CHECK(white.Kd[2] == 0.68);
  CHECK(light.name == "light");
  CHECK((light.Ke == Rgb(17, 12, 4)).all());
  CHECK((light.Kd == 0.78).all());
  CHECK(material(21).name == "green");
  CHECK(material(24).name == "red");
  CHECK(material(24).Kd[1] == 0.065);
  int emitters = 0;
  for (std::size_t f = 0; f < mesh.face_count(); ++f) emitters += (material(f).Ke > 0).any();
  CHECK(emitters == 1);

  // Areas of the groups equal those of the page's quads (the split walls, floor and ceiling are planar).
  auto group_area = [&](std::size_t first, std::size_t count) {
    double a = 0;
    for (std::size_t f = first; f < first + count; ++f) a += face_area(mesh, f);
    return a;
  };
  const double floor = quad_area({552.8, 0, 0}, {0, 0, 0}, {0, 0, 559.2}, {549.6, 0, 559.2});
  const double ceiling = quad_area({556, 548.8, 0}, {556, 548.8, 559.2}, {0, 548.8, 559.2}, {0, 548.8, 0});
  const double back = quad_area({549.6, 0, 559.2}, {0, 0, 559.2}, {0, 548.8, 559.2}, {556, 548.8, 559.2});
  const double right = quad_area({0, 0, 559.2}, {0, 0, 0}, {0, 548.8, 0}, {0, 548.8, 559.2});
  const double light_area = 130.0 * 105.0;
  // Rounding of a sum of a few areas of ~1e5 mm^2: a few ulps each.
  const double tol = 64 * std::numeric_limits<double>::epsilon() * floor;
  CHECK_THAT(group_area(0, 9), Catch::Matchers::WithinAbs(floor, tol));
  CHECK_THAT(group_area(9, 9), Catch::Matchers::WithinAbs(ceiling, tol));
  CHECK_THAT(group_area(9, 1), Catch::Matchers::WithinAbs(light_area, tol));
  CHECK_THAT(group_area(18, 3), Catch::Matchers::WithinAbs(back, tol));
  CHECK_THAT(group_area(21, 3), Catch::Matchers::WithinAbs(right, tol));

  // The measured left wall is not planar: its quads pass the planarity check with a margin, and the whole page
  // quad would too (1.02e-3, below planar_clean).
  const ValidationTolerances tolerances;
  double worst = 0;
  for (std::size_t f = 0; f < mesh.face_count(); ++f) worst = std::max(worst, quad_nonplanarity(mesh, f));
  INFO("largest quad non-planarity " << worst << ", clean limit " << tolerances.planar_clean);
  CHECK(worst > 0);
  CHECK(worst < tolerances.planar_clean);

  // Orientation: walls face the inside of the box, the light faces down.
  const Vec3 centre(278, 274.4, 279.6);
  for (std::size_t f = 0; f < 27; ++f) {
    const Vec3 corner = mesh.vertices[static_cast<std::size_t>(mesh.faces[f][0])];
    INFO("face " << f);
    CHECK(face_vector_area(mesh, f).dot(centre - corner) > 0);
  }
  CHECK(face_vector_area(mesh, 9).normalized().y() == -1.0);
}

TEST_CASE("MTL values are read exactly and mapped to material kinds", "[mesh][read][mtl]") {
  const Mesh mesh = load_scene(data("kinds.obj"));
  REQUIRE(mesh.face_count() == 6);
  auto material = [&](std::size_t f) -> const Material& {
    return mesh.materials[static_cast<std::size_t>(mesh.face_material[f])];
  };
  // 0.73 stays 0.73 (OpenMesh's PLY reader would give 0.7294, tinyobjloader's parser 0.73000000000000009).
  INFO("Kd " << material(0).Kd.transpose());
  CHECK(material(0).Kd[0] == 0.73);
  CHECK(material(0).Kd[1] == 0.725);
  CHECK(material(0).Kd[2] == 0.1);
  CHECK(material(0).Ke[0] == 0.3);
  CHECK(material(0).kind == BsdfKind::diffuse);
  CHECK(material(0).line == 16);  // line of "newmtl exact" in common.mtl
  CHECK(material(0).file.find("common.mtl") != std::string::npos);
  CHECK((material(1).Kd == 0.25).all());  // "Kd 0.25": one value for all channels
  CHECK(material(2).kind == BsdfKind::mirror);
  CHECK(material(2).illum == 3);
  CHECK((material(2).Ks == 0.9).all());
  CHECK(material(2).roughness == 0.0);
  CHECK(material(3).kind == BsdfKind::microfacet);
  CHECK(material(3).roughness == 0.25);  // Pr 0.5 -> alpha = Pr^2
  CHECK(material(4).kind == BsdfKind::dielectric);
  CHECK(material(4).Ni == 1.33);
  CHECK(material(5).kind == BsdfKind::conductor);
  CHECK(material(5).metallic == 1.0);
  CHECK(material(5).roughness == Approx(std::sqrt(2.0 / 100.0)).epsilon(1e-15));  // Ns 98
  // Non-diffuse materials are reported, once per material.
  int notes = 0;
  for (const auto& w : mesh.warnings) notes += w.find("treat it as diffuse") != std::string::npos;
  CHECK(notes == 4);
}

TEST_CASE("PLY: face colours become reflectances, missing colours and repeated indices are reported", "[mesh][ply]") {
  const Mesh cube = load_scene(bundled("cube.ply"));
  REQUIRE(cube.face_count() == 6);
  for (const auto& w : cube.warnings) INFO("warning: " << w);
  REQUIRE(cube.warnings.size() == 1);  // PLY has no emission
  CHECK(cube.warnings[0].find("no emitter") != std::string::npos);
  CHECK(cube.materials.size() == 4);
  CHECK(cube.materials[static_cast<std::size_t>(cube.face_material[2])].Kd[0] == 191.0 / 255.0);
  CHECK(area_of(cube) == 6.0);
  CHECK(cube.face_line[0] == 22);  // ascii: header (13 lines) + 8 vertices + 1
  // Same orientation as cube.obj: normals inward.
  for (std::size_t f = 0; f < 6; ++f) {
    const Vec3 corner = cube.vertices[static_cast<std::size_t>(cube.faces[f][0])];
    CHECK(face_vector_area(cube, f).dot(Vec3(0.5, 0.5, 0.5) - corner) > 0);
  }

  const Mesh plain = load_scene(data("ply_no_colour.ply"));
  CHECK(plain.face_count() == 2);
  CHECK((plain.materials[0].Kd == 0.5).all());
  bool warned = false;
  for (const auto& w : plain.warnings) warned = warned || w.find("no face colours") != std::string::npos;
  CHECK(warned);

  // A triangle with a repeated index has no area: dropped with a repair naming its line (refused with --strict).
  const Mesh repeated = load_scene(data("ply_repeated_index.ply"));
  CHECK(repeated.face_count() == 1);
  bool dropped = false;
  for (const Finding& f : repeated.findings)
    dropped = dropped || (f.line == 15 && f.face == 1 && f.severity == Severity::repair);
  CHECK(dropped);
  ReadOptions strict;
  strict.strict = true;
  CHECK_THROWS_WITH(load_scene(data("ply_repeated_index.ply"), strict),
                    Catch::Contains("ply_repeated_index.ply:15") && Catch::Contains("face 1") &&
                        Catch::Contains("repeated"));
}

TEST_CASE("unknown formats and missing files are input errors", "[mesh][read]") {
  CHECK_THROWS_WITH(read_scene(data("scene.xyz")), Catch::Contains("scene.xyz") && Catch::Contains("unknown scene format '.xyz'"));
  CHECK_THROWS_AS(read_scene(data("does_not_exist.obj")), InputError);
  CHECK_THROWS_WITH(read_scene(data("does_not_exist.obj")), Catch::Contains("cannot open"));
}
