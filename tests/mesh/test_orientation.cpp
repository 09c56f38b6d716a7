// Orientation by shells (mesh/orient_shells.h): a closed cube with faces flipped at random becomes consistent, a
// closed object faces out, an inside-out room is turned to face in, an open shell is reported.
#include <catch2/catch.hpp>

#include <array>
#include <string>
#include <vector>

#include "core/rng.h"
#include "mesh/edge_table.h"
#include "mesh/face_geometry.h"
#include "mesh/orient_shells.h"
#include "mesh/validate.h"

using namespace radwalk;

namespace {

// Appends the box [lo, hi] as 6 quads facing out (or in) with `material`.
void add_box(Mesh& mesh, const Vec3& lo, const Vec3& hi, bool outward, std::int32_t material, std::size_t skip = 6) {
  const auto base = static_cast<std::int32_t>(mesh.vertices.size());
  for (int k = 0; k < 8; ++k)
    mesh.vertices.push_back({(k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(), (k & 4) ? hi.z() : lo.z()});
  // Outward (counter-clockwise seen from outside): -x, +x, -y, +y, -z, +z.
  const std::array<std::array<std::int32_t, 4>, 6> quads = {{{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                                             {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}}};
  for (std::size_t q = 0; q < 6; ++q) {
    if (q == skip) continue;
    std::array<std::int32_t, 4> c = quads[q];
    if (!outward) std::swap(c[1], c[3]);
    for (auto& v : c) v += base;
    mesh.faces.push_back(c);
    mesh.face_material.push_back(material);
  }
}

Mesh with_materials() {
  Mesh mesh;
  mesh.path = "test.obj";
  Material white;
  white.name = "white";
  white.Kd = Rgb::Constant(0.5);
  Material light;
  light.name = "light";
  light.Kd = Rgb::Constant(0.5);
  light.Ke = Rgb::Ones();
  mesh.materials = {white, light};
  return mesh;
}

void flip(Mesh& mesh, std::size_t f) {
  auto& c = mesh.faces[f];
  if (c[3] >= 0) std::swap(c[1], c[3]);
  else std::swap(c[1], c[2]);
}

// Every manifold edge run in opposite directions by its two faces.
bool consistent(const Mesh& mesh) {
  const EdgeTable t = build_edge_table(mesh);
  for (std::size_t e = 0; e < t.edge_count(); ++e)
    if (t.use_count(e) == 2 && t.uses_begin(e)[0].forward == t.uses_begin(e)[1].forward) return false;
  return true;
}

// Whether face f's normal points away from point c.
bool faces_away(const Mesh& mesh, std::size_t f, const Vec3& c) {
  Vec3 centre = Vec3::Zero();
  for (int k = 0; k < mesh.corner_count(f); ++k) centre += mesh.vertices[static_cast<std::size_t>(mesh.faces[f][static_cast<std::size_t>(k)])];
  centre /= mesh.corner_count(f);
  return face_vector_area(mesh, f).dot(centre - c) > 0;
}

}  // namespace

TEST_CASE("a closed cube with random face flips becomes consistent and faces out", "[mesh][orientation]") {
  for (std::uint64_t trial = 0; trial < 20; ++trial) {
    Mesh mesh = with_materials();
    add_box(mesh, {-5, -5, -5}, {5, 5, 5}, false, 0);  // the room, facing in
    add_box(mesh, {0, 0, 0}, {1, 1, 1}, true, 0);       // the cube, faces 6..11
    Rng rng = stream(trial, StreamDomain::test, 0);
    std::size_t flipped = 0;
    for (std::size_t f = 6; f < 12; ++f)
      if (rng.uniform() < 0.5) {
        flip(mesh, f);
        ++flipped;
      }
    INFO("trial " << trial << ", " << flipped << " faces flipped");
    Mesh consistent_only = mesh;
    const OrientationResult c = orient_shells(consistent_only, OrientMode::consistent);
    CHECK(consistent(consistent_only));
    CHECK(c.flipped_faces == std::min(flipped, 6 - flipped));  // the majority kept
    const OrientationResult r = orient_shells(mesh, OrientMode::outward);
    CHECK(consistent(mesh));
    CHECK(r.closed_shells == 2);
    CHECK(r.rooms == 1);
    CHECK(r.flipped_faces == flipped);
    for (std::size_t f = 6; f < 12; ++f) CHECK(faces_away(mesh, f, {0.5, 0.5, 0.5}));
    for (std::size_t f = 0; f < 6; ++f) CHECK_FALSE(faces_away(mesh, f, {0, 0, 0}));
  }
}

TEST_CASE("an inside-out closed room is turned to face in", "[mesh][orientation]") {
  Mesh mesh = with_materials();
  add_box(mesh, {0, 0, 0}, {4, 3, 2.5}, true, 0);  // inside out: the room faces out
  add_box(mesh, {1, 1, 0.5}, {2, 2, 1.5}, true, 0);  // a block inside, correct
  add_box(mesh, {1.5, 1, 2.3}, {2.5, 2, 2.4}, true, 1);  // a lamp (closed, emitting)
  const OrientationResult r = orient_shells(mesh, OrientMode::outward);
  CHECK(r.rooms == 1);
  CHECK(r.flipped_faces == 6);
  for (std::size_t f = 0; f < 6; ++f) CHECK_FALSE(faces_away(mesh, f, {2, 1.5, 1.25}));
  for (std::size_t f = 6; f < 12; ++f) CHECK(faces_away(mesh, f, {1.5, 1.5, 1}));
  // With --orient none nothing moves; consistent keeps the (consistent) inside-out room as it is.
  Mesh none = with_materials();
  add_box(none, {0, 0, 0}, {4, 3, 2.5}, true, 0);
  add_box(none, {1, 1, 0.5}, {2, 2, 1.5}, true, 0);
  CHECK(orient_shells(none, OrientMode::none).flipped_faces == 0);
  CHECK(orient_shells(none, OrientMode::consistent).flipped_faces == 0);
  // Through validate_mesh: one warning with the count.
  Mesh validated = with_materials();
  add_box(validated, {0, 0, 0}, {4, 3, 2.5}, true, 0);
  add_box(validated, {1, 1, 0.5}, {2, 2, 1.5}, true, 1);
  validate_mesh(validated);
  std::size_t warnings = 0;
  for (const Finding& f : validated.findings)
    if (f.kind == "faces flipped") {
      ++warnings;
      CHECK(f.severity == Severity::warning);
      CHECK(f.message.find("6 faces (area 59)") != std::string::npos);
    }
  CHECK(warnings == 1);
}

TEST_CASE("an open shell is reported with the suggestion to make it two-sided", "[mesh][orientation]") {
  Mesh mesh = with_materials();
  add_box(mesh, {-5, -5, -5}, {5, 5, 5}, false, 0);
  add_box(mesh, {0, 0, 0}, {1, 1, 1}, true, 0, 5);  // a box without its top: 5 faces, 4 boundary edges
  flip(mesh, 7);
  const OrientationResult r = orient_shells(mesh, OrientMode::outward);
  REQUIRE(r.open_shells.size() == 1);
  CHECK(r.open_shells[0].faces == 5);
  CHECK(r.open_shells[0].boundary_edges == 4);
  CHECK(r.open_shells[0].first_face == 6);
  CHECK(r.flipped_faces == 1);  // the majority of the open shell kept
  CHECK(consistent(mesh));
  Mesh validated = with_materials();
  add_box(validated, {-5, -5, -5}, {5, 5, 5}, false, 1);
  add_box(validated, {0, 0, 0}, {1, 1, 1}, true, 0, 5);
  ValidationTolerances one_sided;
  one_sided.open_shells = OpenShellSides::one_sided;
  validate_mesh(validated, one_sided);
  bool reported = false;
  for (const Finding& f : validated.findings)
    if (f.kind == "open shell") reported = f.message.find("two-sided") != std::string::npos && f.face == 6;
  CHECK(reported);
}

namespace {

// How many faces carry a two-sided material, and whether a finding of `kind` is there.
std::size_t two_sided_faces(const Mesh& mesh) {
  std::size_t n = 0;
  for (std::int32_t m : mesh.face_material) n += mesh.materials[static_cast<std::size_t>(m)].two_sided;
  return n;
}
bool has_kind(const Mesh& mesh, const std::string& kind) {
  for (const Finding& f : mesh.findings)
    if (f.kind == kind) return true;
  return false;
}

}  // namespace

TEST_CASE("open shells by default (auto): two-sided in a closed room, one-sided in an open scene",
          "[mesh][orientation]") {
  // A closed room (emitting ceiling box) with a bottomless box and a sheet in it: both open shells two-sided by
  // default (6 faces), the room one-sided and facing in; one warning names the count.
  auto room = [] {
    Mesh mesh = with_materials();
    add_box(mesh, {-5, -5, -5}, {5, 5, 5}, false, 1);
    add_box(mesh, {0, 0, 0}, {1, 1, 1}, true, 0, 5);  // open: no top
    const auto base = static_cast<std::int32_t>(mesh.vertices.size());
    mesh.vertices.insert(mesh.vertices.end(), {{2, 2, 2}, {3, 2, 2}, {3, 3, 2}, {2, 3, 2}});
    mesh.faces.push_back({base, base + 1, base + 2, base + 3});  // a sheet
    mesh.face_material.push_back(0);
    return mesh;
  };
  Mesh automatic = room();
  validate_mesh(automatic);
  CHECK(two_sided_faces(automatic) == 6);
  for (std::size_t f = 0; f < 6; ++f) CHECK_FALSE(automatic.materials[static_cast<std::size_t>(automatic.face_material[f])].two_sided);
  CHECK(has_kind(automatic, "open shells made two-sided"));
  CHECK_FALSE(has_kind(automatic, "open shell"));
  // Asked for: one-sided keeps the file's sides (and notes the shells), two-sided is as auto here.
  ValidationTolerances tol;
  tol.open_shells = OpenShellSides::one_sided;
  Mesh one = room();
  validate_mesh(one, tol);
  CHECK(two_sided_faces(one) == 0);
  CHECK(has_kind(one, "open shell"));
  tol.open_shells = OpenShellSides::two_sided;
  Mesh two = room();
  validate_mesh(two, tol);
  CHECK(two_sided_faces(two) == 6);
  // The same room also with --orient none (the room's test does not depend on the mode).
  tol.open_shells = OpenShellSides::automatic;
  tol.orient = OrientMode::none;
  Mesh none = room();
  validate_mesh(none, tol);
  CHECK(two_sided_faces(none) == 6);

  // An open scene (a box without its front, like the Cornell box, with a block): nothing encloses it, so auto
  // keeps every face one-sided and notes the open shell.
  Mesh open = with_materials();
  add_box(open, {-5, -5, -5}, {5, 5, 5}, false, 0, 2);  // no -y wall
  add_box(open, {-1, -1, 4.8}, {1, 1, 4.9}, true, 1);    // a closed lamp
  validate_mesh(open);
  CHECK(two_sided_faces(open) == 0);
  CHECK(has_kind(open, "open shell"));
  CHECK(parse_open_shell_sides("auto") == OpenShellSides::automatic);
  CHECK_THROWS_WITH(parse_open_shell_sides("both"), "--open-shells: 'both' is not one of auto, one-sided, two-sided");
}
