// Coplanar overlapping faces: found with their shared area, named by validation with both faces' objects; faces
// sharing an edge, or parallel a little apart, are not; the search is not quadratic in the face count.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "mesh/coplanar_overlaps.h"
#include "mesh/finding.h"
#include "mesh/validate.h"

using namespace radwalk;

namespace {

constexpr double u = std::numeric_limits<double>::epsilon() / 2;

// Quads from their corners, each its own group, one emitting material.
Mesh mesh_of(const std::vector<std::array<Vec3, 4>>& quads) {
  Mesh mesh;
  mesh.path = "overlap.obj";
  Material light;
  light.name = "light";
  light.Ke = Rgb::Ones();
  mesh.materials = {light};
  for (const auto& q : quads) {
    const auto base = static_cast<std::int32_t>(mesh.vertices.size());
    for (const Vec3& p : q) mesh.vertices.push_back(p);
    mesh.faces.push_back({base, base + 1, base + 2, base + 3});
    mesh.face_material.push_back(0);
    mesh.face_line.push_back(static_cast<long>(mesh.faces.size()));
    mesh.face_group.push_back(static_cast<std::int32_t>(mesh.groups.size()));
    mesh.groups.push_back("object 'o" + std::to_string(mesh.faces.size()) + "'");
    mesh.group_object.push_back("o" + std::to_string(mesh.faces.size()));
    mesh.group_name.push_back("");
  }
  return mesh;
}

// The axis-aligned square [x, x + s] x [y, y + s] in the plane z (counter-clockwise seen from +z).
std::array<Vec3, 4> square(double x, double y, double s, double z = 0) {
  return {Vec3(x, y, z), Vec3(x + s, y, z), Vec3(x + s, y + s, z), Vec3(x, y + s, z)};
}

}  // namespace

TEST_CASE("coplanar faces that overlap are found with their shared area, neighbours and near-parallel faces are not",
          "[mesh][overlaps]") {
  // Squares of side 1: B overlaps A by half (area 0.5), C shares an edge with A, D lies 1e-9 above A, E is A
  // reversed and shifted by a quarter (back to back, area 0.75).
  std::array<Vec3, 4> reversed = square(0.25, 0, 1);
  std::swap(reversed[1], reversed[3]);
  const Mesh mesh = mesh_of({square(0, 0, 1), square(0.5, 0, 1, 0), square(-1, 0, 1), square(0, 0, 1, 1e-9), reversed});
  const auto found = find_coplanar_overlaps(mesh);
  // Pairs: A-B 0.5, A-E 0.75, B-E 0.75 (B = [0.5, 1.5], E = [0.25, 1.25]); C touches A only along an edge and
  // overlaps neither B nor E; D is off their plane by far more than rounding (1e-9 against u ~ 1e-16).
  REQUIRE(found.size() == 3);
  // Areas of unit-size squares clipped in the plane: a few u of rounding per clipped corner.
  const double tolerance = 64 * u;
  CHECK(found[0].face_a == 0);
  CHECK(found[0].face_b == 1);
  CHECK(std::abs(found[0].area - 0.5) <= tolerance);
  CHECK(found[0].same_side);
  CHECK(found[1].face_a == 0);
  CHECK(found[1].face_b == 4);
  CHECK(std::abs(found[1].area - 0.75) <= tolerance);
  CHECK_FALSE(found[1].same_side);
  CHECK(found[2].face_a == 1);
  CHECK(found[2].face_b == 4);
  CHECK(std::abs(found[2].area - 0.75) <= tolerance);
}

TEST_CASE("coplanar overlaps are found in a tilted plane far from the origin, to rounding", "[mesh][overlaps]") {
  // A decal (a small square) on a wall, both in the plane through (1e4, 2e4, 3e4) spanned by two unit vectors that
  // are not axis-aligned: the corners are in one plane only to rounding.
  const Vec3 e1 = Vec3(1, 2, 2) / 3, e2 = Vec3(2, 1, -2) / 3, o(1e4, 2e4, 3e4);
  auto at = [&](double x, double y) -> Vec3 { return o + x * e1 + y * e2; };
  const Mesh mesh = mesh_of({{at(0, 0), at(4, 0), at(4, 3), at(0, 3)}, {at(1, 1), at(2, 1), at(2, 2), at(1, 2)}});
  const auto found = find_coplanar_overlaps(mesh);
  REQUIRE(found.size() == 1);
  // The decal's area 1, its corners rounded to u |o| ~ 4e4 u each: relative error of the area a few u |o|.
  CHECK(std::abs(found[0].area - 1) <= 64 * u * o.norm());
  // The same decal lifted off the wall by 1e-6 (far above the rounding 4 u |o| ~ 1e-11) is not coplanar.
  const Vec3 lift = 1e-6 * e1.cross(e2);
  const Mesh apart = mesh_of({{at(0, 0), at(4, 0), at(4, 3), at(0, 3)},
                              {at(1, 1) + lift, at(2, 1) + lift, at(2, 2) + lift, at(1, 2) + lift}});
  CHECK(find_coplanar_overlaps(apart).empty());
}

TEST_CASE("validation names both overlapping faces, their objects and the shared area", "[mesh][overlaps]") {
  // A and B overlap facing the same way: reported. C lies on A back to back (a block's bottom on a floor: a contact,
  // which patching cuts along): not reported.
  std::array<Vec3, 4> bottom = square(0.25, 0.25, 0.5);
  std::swap(bottom[1], bottom[3]);
  Mesh mesh = mesh_of({square(0, 0, 1), square(0.5, 0, 1), bottom});
  validate_mesh(mesh);
  const Finding* f = nullptr;
  int count = 0;
  for (const Finding& x : mesh.findings)
    if (x.kind == "coplanar overlapping faces") {
      if (!f) f = &x;
      ++count;
    }
  CHECK(count == 1);
  REQUIRE(f != nullptr);
  CHECK(f->severity == Severity::warning);
  CHECK(finding_line(*f) ==
        "overlap.obj:1: face 0: coplanar overlapping faces: this face and face 1 at line 2 (object 'o2', material "
        "'light') lie in one plane and overlap in area 0.5, facing the same way; the radiosity counts the shared area "
        "twice (remove one, or give them a gap) (object 'o1', material 'light')");
}

TEST_CASE("the coplanar-overlap search is linear in the face count on a grid of faces", "[mesh][overlaps]") {
  // A 300 x 300 grid of unit squares (90,000 faces) and one square laid over the middle of four of them. Every face
  // touches at most 8 others (its box meets theirs), so each is tested against at most those: fewer than 5 F pair
  // tests; testing every pair would be F^2 / 2 = 4e9.
  std::vector<std::array<Vec3, 4>> quads;
  const int n = 300;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) quads.push_back(square(i, j, 1));
  quads.push_back(square(149.5, 149.5, 1));
  const Mesh mesh = mesh_of(quads);
  std::size_t tests = 0;
  const auto found = find_coplanar_overlaps(mesh, nullptr, &tests);
  const std::size_t F = mesh.face_count();
  CHECK(tests <= 5 * F);
  REQUIRE(found.size() == 4);
  for (const auto& o : found) {
    CHECK(o.face_b == static_cast<std::int32_t>(F - 1));
    CHECK(std::abs(o.area - 0.25) <= 64 * u * 300);  // coordinates up to 300: rounding u 300 per clipped corner
  }
}
