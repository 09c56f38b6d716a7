// Validation: every malformed input in tests/data gives its specific error or warning, naming file, line and face.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "core/error.h"
#include "mesh/face_geometry.h"
#include "mesh/read_scene.h"
#include "mesh/validate.h"

using namespace radwalk;

namespace {

std::string data(const std::string& name) { return std::string(RADWALK_SOURCE_DIR) + "/tests/data/" + name; }

// The message of the InputError that loading `name` throws ("" if none).
std::string error_of(const std::string& name) {
  try {
    (void)load_scene(data(name));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// The first warning containing every part, or "".
std::string warning_with(const Mesh& mesh, const std::vector<std::string>& parts) {
  for (const auto& w : mesh.warnings) {
    bool all = true;
    for (const auto& p : parts) all = all && contains(w, p);
    if (all) return w;
  }
  return "";
}

// A unit square in the xy plane with an emitting material, named `path` in messages.
Mesh lit_square(const std::string& path) {
  Mesh mesh;
  mesh.path = path;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  mesh.faces = {{0, 1, 2, 3}};
  Material light;
  light.name = "light";
  light.Ke = Rgb::Ones();
  mesh.materials = {light};
  mesh.face_material = {0};
  return mesh;
}

}  // namespace

TEST_CASE("each malformed input is refused with its own one-line message", "[mesh][validate]") {
  struct Case {
    const char* file;
    const char* where;  // "file:line: face F" prefix, or "file:line" when no face is involved
    std::vector<std::string> keys;
  };
  const std::vector<Case> cases = {
      {"truncated_vertex.obj", "truncated_vertex.obj:8:", {"vertex 5", "has 2 numbers", "truncated"}},
      {"bad_index.obj", "bad_index.obj:8: face 1:", {"bad vertex index", "vertex 9", "4 vertices"}},
      {"bad_index_zero.obj", "bad_index_zero.obj:8: face 1:", {"vertex index 0 is invalid"}},
      {"nan_coordinate.obj", "nan_coordinate.obj:7: face 0:", {"vertex 3", "non-finite"}},
      {"missing_mtl.obj", "missing_mtl.obj:1:", {"material library 'does_not_exist.mtl' not found"}},
      {"reflectance_one.obj", "reflectance_one.obj:9: face 1:",
       {"reflectance out of range", "'bright'", "common.mtl:9", "Kd (1, 0.5, 0.5)", "[0, 1)"}},
      {"negative_emission.obj", "negative_emission.obj:9: face 1:",
       {"negative emission", "'negative'", "common.mtl:12", "Ke (-1, 0, 0)"}},
  };
  // Repaired by default, refused with --strict.
  const std::vector<Case> strict_cases = {
      {"zero_area.obj", "zero_area.obj:10: face 1:", {"degenerate face", "area 0", "--strict"}},
      {"nonplanar_quad.obj", "nonplanar_quad.obj:7: face 0:", {"non-planar quad", "split it into two triangles"}},
      {"nonconvex_quad.obj", "nonconvex_quad.obj:7: face 0:", {"non-convex quad", "split it into two triangles"}},
      {"pentagon.obj", "pentagon.obj:8: face 0:", {"has 5 vertices", "triangles and quads", "--strict"}},
      {"truncated_face.obj", "truncated_face.obj:8: face 1:", {"has 2 corners", "--strict"}},
      {"unknown_material.obj", "unknown_material.obj:9: face 1:", {"unknown material 'no_such_material'", "line 8"}},
      {"repeated_index_triangle.obj", "repeated_index_triangle.obj:9: face 1:", {"repeats vertex 2", "--strict"}},
      {"duplicate_face.obj", "duplicate_face.obj:9: face 1:", {"duplicate face", "face 0 (line 7)", "dropped"}},
      {"duplicate_face_reversed.obj", "duplicate_face_reversed.obj:9: face 1:",
       {"duplicate face", "face 0 (line 7)", "facing the other way", "two-sided"}},
  };
  ReadOptions strict;
  strict.strict = true;
  for (const Case& c : strict_cases) {
    std::string message;
    try {
      (void)load_scene(data(c.file), strict);
    } catch (const InputError& e) {
      message = e.what();
    }
    INFO("input " << c.file << " (--strict)\n  message: " << message);
    CHECK(message.rfind(data(c.where), 0) == 0);
    for (const auto& key : c.keys) {
      INFO("expected key: " << key);
      CHECK(contains(message, key));
    }
  }
  for (const Case& c : cases) {
    const std::string message = error_of(c.file);
    INFO("input " << c.file << "\n  message: " << message);
    CHECK(message.rfind(data(c.where), 0) == 0);  // starts with the full path, line and face
    CHECK(message.find('\n') == std::string::npos);
    for (const auto& key : c.keys) {
      INFO("expected key: " << key);
      CHECK(contains(message, key));
    }
  }
}

TEST_CASE("legal oddities are kept with a warning naming the face and line", "[mesh][validate]") {
  struct Case {
    const char* file;
    std::vector<std::string> parts;  // of one warning
  };
  const std::vector<Case> cases = {
      {"nonmanifold_edge.obj", {"nonmanifold_edge.obj:11: face 0:", "non-manifold edge", "shared by 3 faces (0, 1, 2)"}},
      {"nonmanifold_vertex.obj", {"nonmanifold_vertex.obj:10: face 0:", "non-manifold vertex", "vertex 3", "2 fans"}},
      {"flipped_face.obj", {"flipped_face.obj:", "1 faces (area 1) flipped by --orient outward"}},
      {"repeated_index.obj", {"repeated_index.obj:12: face 1:", "repeats vertex 7", "the repeats removed, kept as one face"}},
      {"truncated_face.obj", {"truncated_face.obj:8: face 1:", "has 2 corners", "dropped, area 0"}},
      {"repeated_index_triangle.obj", {"repeated_index_triangle.obj:9: face 1:", "repeats vertex 2", "area 0"}},
      {"duplicate_face.obj", {"duplicate_face.obj:9: face 1:", "duplicate face", "face 0 (line 7)", "dropped (area 1"}},
      {"duplicate_face_reversed.obj", {"duplicate_face_reversed.obj:9: face 1:", "facing the other way", "two-sided"}},
      {"no_material.obj", {"no_material.obj:5: face 0:", "face without material", "radwalk_default"}},
      {"no_material.obj", {"no_material.obj:", "no emitter"}},
      {"zero_area.obj", {"zero_area.obj:10: face 1:", "degenerate face dropped", "area 0", "material 'white'"}},
      {"nonplanar_quad.obj", {"nonplanar_quad.obj:7: face 0:", "non-planar quad split into two triangles"}},
      {"nonconvex_quad.obj", {"nonconvex_quad.obj:7: face 0:", "non-convex quad split", "inner diagonal"}},
      {"pentagon.obj", {"pentagon.obj:8: face 0:", "polygon with 5 vertices triangulated into 3 triangles",
                        "material 'light'"}},
  };
  for (const Case& c : cases) {
    Mesh mesh;
    REQUIRE_NOTHROW(mesh = load_scene(data(c.file)));
    std::vector<std::string> parts = c.parts;
    parts[0] = data(parts[0]);
    const std::string found = warning_with(mesh, parts);
    INFO("input " << c.file);
    for (const auto& w : mesh.warnings) INFO("warning: " << w);
    CHECK(!found.empty());
  }
  // The repair itself: face 1 of repeated_index.obj becomes the triangle 5 6 7 (0-based 4 5 6).
  const Mesh repaired = load_scene(data("repeated_index.obj"));
  CHECK(repaired.faces[1] == std::array<std::int32_t, 4>{4, 5, 6, -1});
  // The triangulated pentagon: 3 triangles of input face 0 tiling its area (1.25), refused with --strict.
  const Mesh pentagon = load_scene(data("pentagon.obj"));
  REQUIRE(pentagon.face_count() == 3);
  double area = 0;
  for (std::size_t f = 0; f < 3; ++f) {
    CHECK(pentagon.source_face(f) == 0);
    CHECK(pentagon.face_line[f] == 8);
    area += face_area(pentagon, f);
  }
  CHECK(area == Approx(1.25).epsilon(1e-15));
  ReadOptions strict;
  strict.strict = true;
  CHECK_THROWS_WITH(load_scene(data("pentagon.obj"), strict),
                    Catch::Contains("pentagon.obj:8: face 0: has 5 vertices") &&
                        Catch::Contains("(material 'light')") && Catch::Contains("--strict"));
  // Faces without material get rho 0.5 and no emission.
  const Mesh plain = load_scene(data("no_material.obj"));
  const Material& m = plain.materials[static_cast<std::size_t>(plain.face_material[0])];
  CHECK((m.Kd == 0.5).all());
  CHECK((m.Ke == 0.0).all());
}

TEST_CASE("validation of programmatic meshes: NaN, index range, warning cap", "[mesh][validate]") {
  const Mesh mesh = lit_square("generated");

  Mesh ok = mesh;
  REQUIRE_NOTHROW(validate_mesh(ok));
  CHECK(ok.warnings.empty());
  CHECK(ok.face_line == std::vector<long>{0});

  Mesh nan = mesh;
  nan.vertices[2].x() = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(validate_mesh(nan), Catch::StartsWith("generated: face 0: vertex 3 has a non-finite"));

  Mesh range = mesh;
  range.faces[0][3] = 4;
  CHECK_THROWS_WITH(validate_mesh(range), Catch::Contains("bad vertex index: vertex 5"));

  Mesh bad_material = mesh;
  bad_material.face_material = {3};
  CHECK_THROWS_WITH(validate_mesh(bad_material), Catch::Contains("material index 3 out of range"));

  Mesh empty;
  empty.path = "empty";
  CHECK_THROWS_WITH(validate_mesh(empty), Catch::Contains("no faces"));

  // Many faces without material: at most max_warnings_per_kind lines plus one summary.
  Mesh many = mesh;
  for (int i = 1; i <= 30; ++i) {
    const auto base = static_cast<std::int32_t>(many.vertices.size());
    many.vertices.push_back({0, 0, double(i)});
    many.vertices.push_back({1, 0, double(i)});
    many.vertices.push_back({1, 1, double(i)});
    many.faces.push_back({base, base + 1, base + 2, -1});
    many.face_material.push_back(-1);
  }
  validate_mesh(many);
  CHECK(many.warnings.size() == 11);
  CHECK(contains(many.warnings.back(), "face without material: 20 more (30 in all)"));
}

TEST_CASE("scenes too large, too small or far from the origin for single precision are caught", "[mesh][validate]") {
  // W1, W2, P4: a closed furnace at 1e19 "converged" to a wrong B; coordinates of 1e77 overflowed areas to inf
  // and passed; a scene at 1e-100 was refused as degenerate with a diagonal of 0.
  auto square = [](double scale, double offset) {
    Mesh mesh = lit_square("scaled");
    mesh.vertices = {{offset, 0, 0}, {offset + scale, 0, 0}, {offset + scale, scale, 0}, {offset, scale, 0}};
    return mesh;
  };
  for (double scale : {1e-6, 1.0, 1e6, 1e12}) {
    Mesh ok = square(scale, 0);
    INFO("scale " << scale);
    CHECK_NOTHROW(validate_mesh(ok));
    CHECK(ok.warnings.empty());
  }
  for (double scale : {1e19, 1e77, 1e300}) {
    Mesh big = square(scale, 0);
    INFO("scale " << scale);
    CHECK_THROWS_WITH(validate_mesh(big), Catch::Contains("too large for single-precision"));
  }
  Mesh tiny = square(1e-100, 0);
  CHECK_THROWS_WITH(validate_mesh(tiny), Catch::Contains("too small") && Catch::Contains("extent 1.41421e-100"));
  // A 1 m square 1e6 m from the origin: traced in float it resolves only about 0.06 m.
  Mesh far = square(1, 1e6);
  REQUIRE_NOTHROW(validate_mesh(far));
  CHECK(!warning_with(far, {"far from the origin", "move the origin"}).empty());
}

TEST_CASE("a self-intersecting (bow-tie) quad off its plane is refused, a planar one is split", "[mesh][validate]") {
  // W3: v 0 0 0 / v 1 0 0 / v 1 1 0 / v 2 1 0 / f 1 2 3 4 has zero vector area and passed validation. Planar, it is
  // now split at its crossing into its two lobes (tests/mesh/test_polygon_crossings.cpp).
  Mesh mesh;
  mesh.path = "bowtie";
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {2, 1, 0}};
  mesh.faces = {{0, 1, 2, 3}};
  mesh.face_material = {-1};
  Mesh planar = mesh;
  REQUIRE_NOTHROW(validate_mesh(planar));
  CHECK(planar.face_count() == 2);
  // A grossly folded (non-planar) quad whose halves nearly cancel: corner 2 lifted by half the quad's width.
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.5}, {2, 1, 0}};
  CHECK_THROWS_WITH(validate_mesh(mesh), Catch::StartsWith("bowtie: face 0: self-intersecting or folded quad"));
}

TEST_CASE("the planarity and degeneracy limits separate the cases they are meant to", "[mesh][validate]") {
  // A unit square with one corner lifted by h: non-planarity grows linearly with h. The limits of
  // ValidationTolerances refuse a lift of 2 % of the diagonal (the width of a square) and accept a lift of 0.1 %.
  const ValidationTolerances tol;
  auto lifted = [](double h) {
    Mesh m;
    m.path = "lifted";
    m.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, h}, {0, 1, 0}};
    m.faces = {{0, 1, 2, 3}};
    Material light;
    light.Ke = Rgb::Ones();
    m.materials = {light};
    m.face_material = {0};
    return m;
  };
  Mesh small = lifted(0.001 * std::sqrt(2.0));
  Mesh medium = lifted(0.02 * std::sqrt(2.0));
  Mesh large = lifted(0.08 * std::sqrt(2.0));
  INFO("non-planarity " << quad_nonplanarity(small, 0) << ", " << quad_nonplanarity(medium, 0) << ", "
                        << quad_nonplanarity(large, 0));
  CHECK(quad_nonplanarity(small, 0) < tol.planar_clean);
  CHECK(quad_nonplanarity(medium, 0) > tol.planar_clean);
  CHECK(quad_nonplanarity(medium, 0) < tol.planar_error);
  CHECK(quad_nonplanarity(large, 0) > tol.planar_error);
  REQUIRE_NOTHROW(validate_mesh(small));
  CHECK(small.warnings.empty());
  REQUIRE_NOTHROW(validate_mesh(medium));
  CHECK(!warning_with(medium, {"slightly non-planar quad"}).empty());
  Mesh large_strict = large;
  ValidationTolerances strict = tol;
  strict.strict = true;
  CHECK_THROWS_WITH(validate_mesh(large_strict, strict), Catch::Contains("non-planar quad"));
  REQUIRE_NOTHROW(validate_mesh(large));
  CHECK(large.face_count() == 2);  // split into two triangles of input face 0
  CHECK(large.source_face(1) == 0);
  CHECK(!warning_with(large, {"non-planar quad split"}).empty());

  // A sliver triangle in a unit scene: refused below degenerate_area x diagonal^2, accepted above.
  auto sliver = [](double height) {
    Mesh m;
    m.path = "sliver";
    m.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {3, 0, 0}, {2.5, height, 0}};
    m.faces = {{0, 1, 2, 3}, {4, 5, 6, -1}};
    Material light;
    light.Ke = Rgb::Ones();
    m.materials = {light};
    m.face_material = {0, 0};
    return m;
  };
  const double diagonal2 = 9.0 + 1.0;  // bounding box 3 x 1 x 0
  Mesh thin = sliver(2 * 0.5 * tol.degenerate_area * diagonal2);   // area = half the limit
  Mesh fine = sliver(2 * 2.0 * tol.degenerate_area * diagonal2);   // area = twice the limit
  Mesh thin_strict = thin;
  CHECK_THROWS_WITH(validate_mesh(thin_strict, strict), Catch::Contains("sliver: face 1: degenerate face"));
  REQUIRE_NOTHROW(validate_mesh(thin));  // dropped, with a warning
  CHECK(thin.face_count() == 1);
  CHECK(!warning_with(thin, {"sliver:", "face 1", "degenerate face dropped"}).empty());
  CHECK_NOTHROW(validate_mesh(fine));
  CHECK(fine.face_count() == 2);
}
