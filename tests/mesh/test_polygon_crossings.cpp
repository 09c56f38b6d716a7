// Self-intersecting polygons split at their crossings into simple pieces: figure-eights (lobes cancelling or
// not), a 37-gon crossing itself, a bow-tie quad, a figure-eight through one corner, a pentagram; their area kept
// (the lobes' areas as drawn), every piece facing one way, the repair named; what cannot be split refused.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "mesh/finding.h"
#include "mesh/polygon_crossings.h"
#include "mesh/read_obj.h"
#include "mesh/validate.h"

using namespace radwalk;

namespace {

constexpr double u = std::numeric_limits<double>::epsilon() / 2;

// A point of the tilted plane through (3, -2, 5) with orthonormal axes e1, e2 (normal e1 x e2).
struct Plane {
  Vec3 e1 = Vec3(1, 0.2, 0.1).normalized();
  Vec3 e2 = Vec3(0, 1, 0).cross(e1).normalized().cross(e1);
  Vec3 at(double x, double y) const { return Vec3(3, -2, 5) + x * e1 + y * e2; }
  Vec3 normal() const { return e1.cross(e2); }
};

// Twice the signed shoelace area of 2D points.
double shoelace(const std::vector<Eigen::Vector2d>& p) {
  double s = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    const auto &a = p[k], &b = p[(k + 1) % p.size()];
    s += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * s;
}

struct Triangles {
  double area = 0;        // sum of the triangles' areas
  bool one_way = true;    // every triangle's normal points the same way as the first's
  Vec3 first = Vec3::Zero();
};
Triangles triangles_of(const std::vector<Vec3>& corners, const PolygonPieces& pieces) {
  const auto t = triangulate_pieces(corners, pieces);
  REQUIRE(t);
  Triangles r;
  for (const auto& tri : *t) {
    auto point = [&](std::int32_t k) {
      const auto i = static_cast<std::size_t>(k);
      return i < corners.size() ? corners[i] : pieces.new_points[i - corners.size()];
    };
    const Vec3 v = 0.5 * (point(tri[1]) - point(tri[0])).cross(point(tri[2]) - point(tri[0]));
    if (r.first == Vec3::Zero()) r.first = v;
    r.one_way = r.one_way && v.dot(r.first) > 0;
    r.area += v.norm();
  }
  return r;
}

MtlSource no_libraries() {
  return {[](const std::string&) { return false; }, [](const std::string&) { return std::string(); }};
}

const Finding* first_of(const std::vector<Finding>& findings, const std::string& kind) {
  for (const Finding& f : findings)
    if (f.kind == kind) return &f;
  return nullptr;
}

}  // namespace

TEST_CASE("a symmetric figure-eight is split at its crossing into its two lobes, keeping their area",
          "[mesh][crossings]") {
  // Lobes (-1,-1) (-2,0) (-1,1) X and X (1,-1) (2,0) (1,1) about the crossing X = origin: 2 each, opposite windings,
  // so the vector area is 0 (formerly dropped as "no area"). In a tilted plane far from the origin.
  const Plane plane;
  const std::vector<Vec3> p = {plane.at(-2, 0), plane.at(-1, 1), plane.at(1, -1),
                               plane.at(2, 0),  plane.at(1, 1),  plane.at(-1, -1)};
  const PolygonPieces pieces = split_at_crossings(p, false);
  REQUIRE(pieces.status == PolygonPieces::Status::split);
  CHECK(pieces.meetings == 1);
  REQUIRE(pieces.pieces.size() == 2);
  CHECK(pieces.reversed == 1);
  REQUIRE(pieces.new_points.size() == 1);
  // The crossing point: the two edges meet at the plane's origin; coordinates of size R = 8 (the plane's offset)
  // carry 4 u R of rounding through the projection and back.
  CHECK((pieces.new_points[0] - plane.at(0, 0)).norm() <= 64 * u * 8);
  // Area: coordinates of size R round the projected points to 4 u R, so each shoelace term (two products of
  // coordinates at most 2 apart from the centroid) to 16 u R; 6 terms.
  const double tolerance = 6 * 16 * u * 8 * 2;
  CHECK(std::abs(pieces.area - 4) <= tolerance);
  const Triangles t = triangles_of(p, pieces);
  CHECK(std::abs(t.area - 4) <= tolerance);
  CHECK(t.one_way);
  // The dominant orientation of a polygon whose lobes cancel: that of the lobe holding corner 0, the left one,
  // which turns clockwise in (e1, e2).
  CHECK(t.first.dot(plane.normal()) < 0);
}

TEST_CASE("a 37-gon whose outline crosses itself is split into simple pieces of the lobes' area", "[mesh][crossings]") {
  // A lemniscate of Gerono x = cos s, y = sin s cos s sampled at 37 points: it crosses itself once near the origin,
  // its right lobe counter-clockwise, its left lobe clockwise (sizes differ: 37 is odd). The expected area is the
  // sum of the lobes' shoelace areas, each closed through the crossing point of the two edges that change the sign
  // of x (computed here independently).
  std::vector<Eigen::Vector2d> q;
  for (int k = 0; k < 37; ++k) {
    const double s = 2 * M_PI * k / 37 + 0.1;
    q.emplace_back(std::cos(s), std::sin(s) * std::cos(s));
  }
  std::vector<std::size_t> changes;  // edges k -> k+1 along which x changes sign
  for (std::size_t k = 0; k < q.size(); ++k)
    if ((q[k].x() < 0) != (q[(k + 1) % q.size()].x() < 0)) changes.push_back(k);
  REQUIRE(changes.size() == 2);
  auto point = [&](std::size_t k) { return q[k % q.size()]; };
  const Eigen::Vector2d a = point(changes[0]), b = point(changes[0] + 1), c = point(changes[1]), d = point(changes[1] + 1);
  const double t = ((c - a).x() * (d - c).y() - (c - a).y() * (d - c).x()) /
                   ((b - a).x() * (d - c).y() - (b - a).y() * (d - c).x());
  const Eigen::Vector2d X = a + t * (b - a);
  std::vector<Eigen::Vector2d> one = {X}, other = {X};
  for (std::size_t k = changes[0] + 1; k <= changes[1]; ++k) one.push_back(q[k]);
  for (std::size_t k = changes[1] + 1; k <= changes[0] + q.size(); ++k) other.push_back(point(k));
  const double A1 = shoelace(one), A2 = shoelace(other);
  REQUIRE(A1 * A2 < 0);  // lobes of opposite windings
  const double expected = std::abs(A1) + std::abs(A2);

  const Plane plane;
  std::vector<Vec3> p;
  for (const auto& x : q) p.push_back(plane.at(x.x(), x.y()));
  const PolygonPieces pieces = split_at_crossings(p, false);
  REQUIRE(pieces.status == PolygonPieces::Status::split);
  CHECK(pieces.meetings == 1);
  CHECK(pieces.pieces.size() == 2);
  CHECK(pieces.reversed == 1);
  // 39 shoelace terms of 16 u R each (R = 8, the plane's offset, against coordinates at most 1 from the centroid).
  const double tolerance = 39 * 16 * u * 8;
  CHECK(std::abs(pieces.area - expected) <= tolerance);
  const Triangles tr = triangles_of(p, pieces);
  CHECK(std::abs(tr.area - expected) <= tolerance);
  CHECK(tr.one_way);
  // Dominant orientation: the larger lobe's.
  CHECK(tr.first.dot(plane.normal()) * (std::abs(A1) > std::abs(A2) ? A1 : A2) > 0);

  // Off its plane (a corner lifted by 5 % of the size), the crossing is not one in space: refused.
  std::vector<Vec3> bent = p;
  bent[3] += 0.1 * plane.normal();
  const PolygonPieces refused = split_at_crossings(bent, false);
  CHECK(refused.status == PolygonPieces::Status::nonplanar);
  CHECK(refused.pieces.empty());
}

TEST_CASE("a figure-eight through one corner and a pentagram are split, a simple polygon is left whole",
          "[mesh][crossings]") {
  // Corner 0 visited twice: lobes (0,0) (-1,1) (-1,-1) [+1] and (0,0) (1,1) (1,-1) [-1]. Without touches it is
  // simple (no proper crossing); with them, two lobes of area 1.
  const std::vector<Vec3> eight = {{0, 0, 0}, {-1, 1, 0}, {-1, -1, 0}, {0, 0, 0}, {1, 1, 0}, {1, -1, 0}};
  CHECK(split_at_crossings(eight, false).status == PolygonPieces::Status::simple);
  const PolygonPieces touched = split_at_crossings(eight, true);
  REQUIRE(touched.status == PolygonPieces::Status::split);
  CHECK(touched.new_points.empty());
  CHECK(touched.pieces.size() == 2);
  CHECK(touched.area == 2);  // small integers: exact
  CHECK(triangles_of(eight, touched).one_way);

  // A pentagram in one stroke: 5 crossings, nested pieces (the star's outline and its inner pentagon, where the
  // winding number is 2); the inner one is left out, so the centre is covered once: the area is the star's,
  // |vector area| (which counts the centre twice) less the inner pentagon's, (5/2) r^2 sin(72 deg) with
  // r = cos(72 deg) / cos(36 deg).
  std::vector<Vec3> star;
  for (int k = 0; k < 5; ++k) {
    const double a = M_PI / 2 + 4 * M_PI * k / 5;
    star.emplace_back(std::cos(a), std::sin(a), 0);
  }
  Vec3 N = Vec3::Zero();
  for (std::size_t k = 0; k < 5; ++k) N += 0.5 * star[k].cross(star[(k + 1) % 5]);
  const PolygonPieces pentagram = split_at_crossings(star, false);
  REQUIRE(pentagram.status == PolygonPieces::Status::split);
  CHECK(pentagram.meetings == 5);
  CHECK(pentagram.reversed == 0);
  CHECK(pentagram.nested == 1);
  CHECK(pentagram.pieces.size() == 1);
  const double r = std::cos(2 * M_PI / 5) / std::cos(M_PI / 5);
  const double star_area = N.norm() - 2.5 * r * r * std::sin(2 * M_PI / 5);
  CHECK(std::abs(pentagram.area - star_area) <= 16 * 15 * u);  // 15 shoelace terms of size 1
  const Triangles t = triangles_of(star, pentagram);
  CHECK(std::abs(t.area - star_area) <= 16 * 15 * u);
  CHECK(t.one_way);

  // A simple concave polygon (an L) has no crossing.
  CHECK(split_at_crossings({{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}}, true).status ==
        PolygonPieces::Status::simple);
}

TEST_CASE("reading a self-intersecting polygon repairs it with a finding naming the face, object and area, --strict "
          "refuses it",
          "[mesh][crossings]") {
  const std::string obj =
      "v -2 0 0\nv -1 1 0\nv 1 -1 0\nv 2 0 0\nv 1 1 0\nv -1 -1 0\nv 0 0 3\nv 1 0 3\nv 0 1 3\n"
      "o eight\ng lobes\nf 1 2 3 4 5 6\nf 7 8 9\n";
  Mesh mesh = read_obj_text("eight.obj", obj, no_libraries());
  const Finding* f = first_of(mesh.findings, "self-intersecting polygon split");
  REQUIRE(f != nullptr);
  CHECK(f->severity == Severity::repair);
  const std::string line = finding_line(*f);
  CHECK(line ==
        "eight.obj:12: face 0: polygon with 6 vertices crosses itself: split at 1 crossing into 2 simple pieces of "
        "area 4 in all (the lobes' areas as drawn), 1 lobe turned to face along the polygon's dominant normal, 4 "
        "triangles; the crossing is new vertex 10 (--strict refuses it) (object 'eight', group 'lobes')");
  REQUIRE(mesh.faces.size() == 5);
  CHECK(mesh.vertices.size() == 10);  // the crossing point added
  CHECK(mesh.vertices[9] == Vec3(0, 0, 0));
  validate_mesh(mesh);
  double area = 0;
  for (std::size_t k = 0; k < 4; ++k) {
    CHECK(mesh.face_source[k] == 0);
    const auto& c = mesh.faces[k];
    area += 0.5 * (mesh.vertices[static_cast<std::size_t>(c[1])] - mesh.vertices[static_cast<std::size_t>(c[0])])
                      .cross(mesh.vertices[static_cast<std::size_t>(c[2])] - mesh.vertices[static_cast<std::size_t>(c[0])])
                      .norm();
  }
  CHECK(area == 4);  // small integers and the crossing at the origin: exact

  ReadOptions strict;
  strict.strict = true;
  Mesh refused = read_obj_text("eight.obj", obj, no_libraries(), strict);
  CHECK_THROWS_WITH(validate_mesh(refused), Catch::StartsWith("eight.obj:12: face 0: has 6 vertices"));
}

TEST_CASE("a planar bow-tie quad is split into its two lobes, a folded one and --strict refuse it", "[mesh][crossings]") {
  // v 0 0 0 / v 1 0 0 / v 1 1 0 / v 2 1 0 / f 1 2 3 4: edges 1-2 and 3-0 cross at (1, 0.5); lobes of 0.25 each,
  // opposite windings (vector area 0). Formerly refused.
  auto bowtie = [](double lift) {
    Mesh mesh;
    mesh.path = "bowtie";
    mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, lift}, {2, 1, 0}, {0, 0, 5}, {1, 0, 5}, {0, 1, 5}};
    mesh.faces = {{0, 1, 2, 3}, {4, 5, 6, -1}};
    Material light;
    light.name = "light";
    light.Ke = Rgb::Ones();
    mesh.materials = {light};
    mesh.face_material = {0, 0};
    return mesh;
  };
  Mesh mesh = bowtie(0);
  validate_mesh(mesh);
  const Finding* f = first_of(mesh.findings, "self-intersecting polygon split");
  REQUIRE(f != nullptr);
  CHECK(finding_line(*f) ==
        "bowtie: face 0: quad crosses itself: split at 1 crossing into 2 simple pieces of area 0.5 in all (the lobes' "
        "areas as drawn), 1 lobe turned to face along the polygon's dominant normal, 2 triangles; the crossing is new "
        "vertex 8 (--strict refuses it) (material 'light')");
  REQUIRE(mesh.face_count() == 3);
  CHECK(mesh.vertices.back() == Vec3(1, 0.5, 0));
  double area = 0;
  Vec3 first = Vec3::Zero();
  for (std::size_t k = 0; k < 3; ++k) {
    if (mesh.face_source[k] != 0) continue;
    const auto& c = mesh.faces[k];
    CHECK(c[3] == -1);
    const Vec3 v = 0.5 * (mesh.vertices[static_cast<std::size_t>(c[1])] - mesh.vertices[static_cast<std::size_t>(c[0])])
                             .cross(mesh.vertices[static_cast<std::size_t>(c[2])] - mesh.vertices[static_cast<std::size_t>(c[0])]);
    if (first == Vec3::Zero()) first = v;
    CHECK(v.dot(first) > 0);  // one orientation
    area += v.norm();
  }
  CHECK(area == 0.5);

  ValidationTolerances strict;
  strict.strict = true;
  Mesh refused = bowtie(0);
  CHECK_THROWS_WITH(validate_mesh(refused, strict), Catch::StartsWith("bowtie: face 0: self-intersecting or folded quad"));
  // Folded out of its plane (corner 2 lifted by half the quad's width): refused as before.
  Mesh folded = bowtie(0.5);
  CHECK_THROWS_WITH(validate_mesh(folded), Catch::Contains("face 0: self-intersecting or folded quad"));
}

TEST_CASE("a quad folded off its plane (a bow-tie seen from above) is split along the diagonal whose triangles do not "
          "overlap, --strict refuses it",
          "[mesh][crossings]") {
  // Corners (0,0,0) (1,1,0) (1,0,h) (0,1,h): seen from +z a bow-tie (edges 1-2 and 3-4 cross), seen along its
  // Newell normal (0,-h,0) a rectangle. Vector area h = 0.3 is below half its area: formerly refused as "folded".
  // Both diagonals give two triangles turning the normal's way, each of area sqrt(1 + 2 h^2) / 2; the diagonal 0-2
  // (the first of the tie, triangulate.h) is taken.
  const std::string obj =
      "v 0 0 0\nv 1 1 0\nv 1 0 0.3\nv 0 1 0.3\nv -5 -5 4\nv 5 -5 4\nv 5 5 4\nv -5 5 4\n"
      "o chair\ng seat\nf 1 2 3 4\ng lamp\nf 8 7 6 5\n";
  Mesh mesh = read_obj_text("chair.obj", obj, no_libraries());
  mesh.materials.resize(1);
  mesh.materials[0].name = "m";
  mesh.materials[0].Kd = Rgb::Constant(0.5);
  mesh.materials[0].Ke = Rgb::Ones();
  mesh.face_material.assign(mesh.face_count(), 0);
  Mesh strict_copy = mesh;
  validate_mesh(mesh);
  const Finding* f = first_of(mesh.findings, "folded quad split");
  REQUIRE(f != nullptr);
  CHECK(f->severity == Severity::repair);
  const std::string line = finding_line(*f);
  CHECK(line.find("chair.obj:11: face 0: folded quad split into two triangles along its diagonal 0-2") == 0);
  CHECK(line.find("(object 'chair', group 'seat', material 'm')") != std::string::npos);
  CHECK(line.find("--strict refuses it") != std::string::npos);
  double area = 0;
  Vec3 first = Vec3::Zero();
  std::size_t pieces = 0;
  for (std::size_t k = 0; k < mesh.face_count(); ++k) {
    if (mesh.face_source[k] != 0) continue;
    ++pieces;
    const auto& c = mesh.faces[k];
    REQUIRE(c[3] == -1);
    const Vec3 v = 0.5 * (mesh.vertices[static_cast<std::size_t>(c[1])] - mesh.vertices[static_cast<std::size_t>(c[0])])
                             .cross(mesh.vertices[static_cast<std::size_t>(c[2])] - mesh.vertices[static_cast<std::size_t>(c[0])]);
    if (first == Vec3::Zero()) first = v;
    CHECK(v.dot(Vec3(0, -1, 0)) > 0);  // both turn the Newell normal's way
    area += v.norm();
  }
  CHECK(pieces == 2);
  const double as_drawn = std::sqrt(1 + 2 * 0.3 * 0.3);
  CHECK(std::abs(area - as_drawn) <= 8 * std::numeric_limits<double>::epsilon() * as_drawn);  // to rounding

  ValidationTolerances strict;
  strict.strict = true;
  CHECK_THROWS_WITH(validate_mesh(strict_copy, strict),
                    Catch::StartsWith("chair.obj:11: face 0: self-intersecting or folded quad"));
}
