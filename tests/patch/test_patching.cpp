// Patching: area preserved, faces split on their own (small faces beside big ones stay whole), no patch edge above
// max_edge, no patch area above max_area, attributes kept, stable order.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "core/error.h"
#include "mesh/face_geometry.h"
#include "mesh/read_scene.h"
#include "mesh/validate.h"
#include "patch/display_mesh.h"
#include "patch/patching.h"

using namespace radwalk;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

std::string bundled(const std::string& name) { return std::string(RADWALK_SOURCE_DIR) + "/meshes/" + name; }
std::string data(const std::string& name) { return std::string(RADWALK_SOURCE_DIR) + "/tests/data/" + name; }

using Key = std::array<double, 3>;
Key key_of(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

const Vec3& corner(const Mesh& m, std::size_t f, int k) {
  return m.vertices[static_cast<std::size_t>(m.faces[f][static_cast<std::size_t>(k)])];
}

bool on_segment(const Vec3& q, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double t = (q - a).dot(d) / d.squaredNorm();
  return (q - a).cross(d).norm() <= 1e-9 * d.squaredNorm() && t >= -1e-12 && t <= 1 + 1e-12;
}

// Conformity problems of a patch set (empty when there are none), checked independently of the implementation:
//  - no two points at the same position (a split point made twice is a crack);
//  - a patch side inside its face is used by exactly 2 patches;
//  - unless t_junctions (faces split on their own may cut a shared edge differently): a side on input edge e by
//    exactly as many patches as e has faces (sides are matched by point indices, so a T-junction changes the
//    counts).
std::vector<std::string> conformity_problems(const Mesh& mesh, const PatchSet& s, bool t_junctions = false) {
  std::vector<std::string> problems;
  std::map<Key, int> at;
  for (const Vec3& p : s.points)
    if (++at[key_of(p)] == 2) problems.push_back("two points at " + std::to_string(p.x()) + " " +
                                                  std::to_string(p.y()) + " " + std::to_string(p.z()));
  // Faces per input edge, keyed by endpoint positions.
  std::map<std::pair<Key, Key>, int> faces_on_edge;
  auto edge_key = [](const Vec3& a, const Vec3& b) {
    return key_of(a) < key_of(b) ? std::make_pair(key_of(a), key_of(b)) : std::make_pair(key_of(b), key_of(a));
  };
  for (std::size_t f = 0; f < mesh.face_count(); ++f)
    for (int k = 0; k < mesh.corner_count(f); ++k)
      ++faces_on_edge[edge_key(corner(mesh, f, k), corner(mesh, f, (k + 1) % mesh.corner_count(f)))];
  std::map<std::pair<std::int32_t, std::int32_t>, int> uses;
  for (std::size_t p = 0; p < s.size(); ++p)
    for (int k = 0; k < s.corner_count(p); ++k) {
      const std::int32_t a = s.corners[p][static_cast<std::size_t>(k)];
      const std::int32_t b = s.corners[p][static_cast<std::size_t>((k + 1) % s.corner_count(p))];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  for (std::size_t p = 0; p < s.size(); ++p) {
    const auto f = static_cast<std::size_t>(s.face[p]);
    for (int k = 0; k < s.corner_count(p); ++k) {
      const std::int32_t a = s.corners[p][static_cast<std::size_t>(k)];
      const std::int32_t b = s.corners[p][static_cast<std::size_t>((k + 1) % s.corner_count(p))];
      int expected = 2;
      bool on_boundary = false;
      for (int j = 0; j < mesh.corner_count(f); ++j) {
        const Vec3& c0 = corner(mesh, f, j);
        const Vec3& c1 = corner(mesh, f, (j + 1) % mesh.corner_count(f));
        if (on_segment(s.points[static_cast<std::size_t>(a)], c0, c1) &&
            on_segment(s.points[static_cast<std::size_t>(b)], c0, c1)) {
          expected = faces_on_edge[edge_key(c0, c1)];
          on_boundary = true;
        }
      }
      const int used = uses[{std::min(a, b), std::max(a, b)}];
      if (on_boundary && t_junctions) continue;
      if (used != expected)
        problems.push_back("patch " + std::to_string(p) + " side " + std::to_string(k) + ": used by " +
                           std::to_string(used) + " patches, expected " + std::to_string(expected));
    }
  }
  return problems;
}

// Largest angle between a triangle of the fan of a polygon and the unit normal n.
double tilt(const Vec3& n, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 t = (b - a).cross(c - a);
  return t.norm() > 0 ? std::acos(std::min(1.0, std::abs(t.normalized().dot(n)))) : 0.0;
}

// Checks everything the patching promises for one mesh and max_edge (and max_area if > 0). conforming: the faces
// are known to be cut alike along every shared edge, so there is no T-junction either.
void check_patching(const Mesh& mesh, const PatchSet& s, double max_edge, bool conforming = true,
                    double max_area = 0) {
  // Order and attributes: faces in order; rho, E, material from the face's material.
  REQUIRE(s.size() >= mesh.face_count());
  std::vector<double> area(mesh.face_count(), 0.0);
  std::vector<int> count(mesh.face_count(), 0);
  std::vector<double> worst_tilt(mesh.face_count(), 0.0);
  std::vector<Vec3> n(mesh.face_count());
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    n[f] = face_vector_area(mesh, f).normalized();
    worst_tilt[f] = tilt(n[f], corner(mesh, f, 0), corner(mesh, f, 1), corner(mesh, f, 2));
    if (mesh.is_quad(f))
      worst_tilt[f] = std::max(worst_tilt[f], tilt(n[f], corner(mesh, f, 0), corner(mesh, f, 2), corner(mesh, f, 3)));
  }
  double longest = 0;
  for (std::size_t p = 0; p < s.size(); ++p) {
    INFO("patch " << p << " of face " << s.face[p]);
    if (p > 0) REQUIRE(s.face[p] >= s.face[p - 1]);
    const auto f = static_cast<std::size_t>(s.face[p]);
    const Material& m = mesh.materials[static_cast<std::size_t>(mesh.face_material[f])];
    REQUIRE(s.material[p] == mesh.face_material[f]);
    REQUIRE((s.rho[p] == m.Kd).all());
    REQUIRE((s.E[p] == kPi * m.Ke).all());
    REQUIRE(s.normal[p].dot(n[f]) > 0);  // same orientation as the face
    area[f] += s.area[p];
    ++count[f];
    if (max_area > 0) CHECK(s.area[p] <= max_area * (1 + 64 * kEps));
    for (int k = 0; k < s.corner_count(p); ++k)
      longest = std::max(longest, (s.corner(p, (k + 1) % s.corner_count(p)) - s.corner(p, k)).norm());
    const Vec3 &a = s.corner(p, 0), &b = s.corner(p, 1), &c = s.corner(p, 2);
    worst_tilt[f] = std::max(worst_tilt[f], tilt(n[f], a, b, c));
    if (s.is_quad(p)) worst_tilt[f] = std::max(worst_tilt[f], tilt(n[f], a, c, s.corner(p, 3)));
  }
  // No patch edge longer than max_edge (up to the rounding of the split points).
  if (max_edge > 0) {
    INFO("longest patch edge " << longest << ", max_edge " << max_edge);
    CHECK(longest <= max_edge * (1 + 16 * kEps));
  }
  // Per-face area: equal up to rounding (k terms of a few ulps each) for a planar face; for a slightly non-planar
  // quad both areas lie between the projected area A_proj and A_proj / cos(largest tilt of any triangle).
  double total_faces = 0, total_patches = 0, total_tol = 0;
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const double expected = face_area(mesh, f);
    const double tol = expected * (64 * count[f] * kEps + (1 / std::cos(worst_tilt[f]) - 1));
    INFO("face " << f << ": patch areas sum to " << area[f] << ", face area " << expected << ", tolerance " << tol
                 << " (" << count[f] << " patches, tilt " << worst_tilt[f] << ")");
    CHECK(std::abs(area[f] - expected) <= tol);
    total_faces += expected;
    total_patches += area[f];
    total_tol += tol + 2 * mesh.face_count() * kEps * expected;  // + rounding of the two sums
  }
  INFO("total area of patches " << total_patches << ", of faces " << total_faces << ", tolerance " << total_tol);
  CHECK(std::abs(total_patches - total_faces) <= total_tol);
  // No cracks, and where the faces are cut alike no T-junctions.
  const auto problems = conformity_problems(mesh, s, !conforming);
  for (std::size_t i = 0; i < problems.size() && i < 10; ++i) UNSCOPED_INFO(problems[i]);
  CHECK(problems.empty());
}

}  // namespace

TEST_CASE("max_edge <= 0 keeps input faces: patch i is face i", "[patch]") {
  for (const char* file : {"cornell_box.obj", "cube.obj", "furnace.obj", "parallel_squares.obj",
                           "perpendicular_squares.obj", "cube.ply"}) {
    INFO(file);
    const Mesh mesh = load_scene(bundled(file));
    for (const double max_edge : {0.0, -1.0}) {
      const PatchSet s = make_patches(mesh, max_edge);
      REQUIRE(s.size() == mesh.face_count());
      CHECK(s.source == mesh.path);
      CHECK(s.materials.size() == mesh.materials.size());
      for (std::size_t i = 0; i < s.size(); ++i) {
        INFO("patch " << i);
        CHECK(s.face[i] == static_cast<std::int32_t>(i));
        REQUIRE(s.corner_count(i) == mesh.corner_count(i));
        for (int k = 0; k < s.corner_count(i); ++k) CHECK(s.corner(i, k) == corner(mesh, i, k));
        CHECK(s.area[i] == face_area(mesh, i));
      }
      check_patching(mesh, s, max_edge);
    }
  }
}

TEST_CASE("subdivided bundled meshes: area kept, conforming, edges bounded, attributes kept", "[patch]") {
  struct Case {
    const char* file;
    double max_edge;
    std::size_t patches;  // expected count, 0 if not known in closed form
  };
  for (const Case c : {Case{"cube.obj", 1.0, 6}, Case{"cube.obj", 0.999, 24}, Case{"cube.obj", 0.25, 96},
                       Case{"cube.obj", 0.3, 96}, Case{"furnace.obj", 0.1, 600}, Case{"cube.ply", 0.5, 24},
                       Case{"parallel_squares.obj", 0.2, 50}, Case{"perpendicular_squares.obj", 0.5, 8},
                       Case{"cornell_box.obj", 100.0, 0}, Case{"cornell_box.obj", 50.0, 0},
                       Case{"cornell_box.obj", 20.0, 0}}) {
    INFO(c.file << " at max_edge " << c.max_edge);
    const Mesh mesh = load_scene(bundled(c.file));
    const PatchSet s = make_patches(mesh, c.max_edge);
    if (c.patches) CHECK(s.size() == c.patches);
    check_patching(mesh, s, c.max_edge);
  }
}

TEST_CASE("the Cornell box at max_edge 50 has a reasonable patch count", "[patch][cornell]") {
  const Mesh mesh = load_scene(bundled("cornell_box.obj"));
  const PatchSet s = make_patches(mesh, 50.0);
  // Every patch is a quad with sides <= 50, so its area is <= 2500: the count is at least area / 2500. Splits
  // only round up per edge class, so a count far above that bound would mean needless splitting.
  const double lower = s.total_area() / (50.0 * 50.0);
  INFO("Cornell box at max_edge 50: " << s.size() << " patches, total area " << s.total_area()
                                      << " mm^2, lower bound " << lower);
  CHECK(s.size() >= lower);
  CHECK(s.size() <= 2 * lower);
  CHECK(s.size() == 975);  // reported in meshes/README.md
}

TEST_CASE("triangles and quads sharing edges are split each on its own", "[patch]") {
  // A unit quad with a triangle on its right side and a second triangle on top of it. Each face is split by its own
  // longest edge: the quad's sides are 1 -> 2 x 2 quads at max_edge 0.5; the triangles' slanted sides sqrt(1.25) =
  // 1.118 -> m = 3, 9 triangles each: 4 + 9 + 9 = 22 patches (the former conforming split, which passed the
  // triangles' 3 parts on to the quad, gave 27). The shared edges are cut in 2 on one side, 3 on the other:
  // T-junctions, no cracks.
  Mesh mesh;
  mesh.path = "generated";
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0.5, 0}, {0.5, 2, 0}};
  mesh.faces = {{0, 1, 2, 3}, {1, 4, 2, -1}, {3, 2, 5, -1}};
  Material light;
  light.name = "light";
  light.Kd = Rgb(0.1, 0.2, 0.3);
  light.Ke = Rgb(1, 2, 3);
  mesh.materials = {light};
  mesh.face_material = {0, 0, 0};
  validate_mesh(mesh);
  REQUIRE(mesh.warnings.empty());
  const PatchSet s = make_patches(mesh, 0.5);
  CHECK(s.size() == 22);
  check_patching(mesh, s, 0.5, false);
  // Uniform splitting of a triangle: all sub-triangles have the same area; so do the quad's.
  for (std::size_t p = 0; p < s.size(); ++p) {
    if (s.face[p] == 0) CHECK(s.area[p] == Approx(0.25).epsilon(1e-13));
    if (s.face[p] == 1) CHECK(s.area[p] == Approx(face_area(mesh, 1) / 9).epsilon(1e-13));
  }
}

// A small quad B = [0, 0.5]^2 beside a long triangle T = (0.5, 0), (4, 0.25), (0.5, 0.5) on B's side x = 0.5.
Mesh small_beside_big() {
  Mesh mesh;
  mesh.path = "generated";
  mesh.vertices = {{0, 0, 0}, {0.5, 0, 0}, {0.5, 0.5, 0}, {0, 0.5, 0}, {4, 0.25, 0}};
  mesh.faces = {{0, 1, 2, 3}, {1, 4, 2, -1}};
  Material white;
  white.name = "white";
  white.Kd = Rgb(0.5, 0.5, 0.5);
  mesh.materials = {white};
  mesh.face_material = {0, 0};
  validate_mesh(mesh);
  return mesh;
}

TEST_CASE("a small face beside a big one is not split: cuts do not propagate", "[patch]") {
  const Mesh mesh = small_beside_big();  // validated (only the "no emitter" notice)
  // T's longest side sqrt(3.5^2 + 0.25^2) = 3.509 -> m = 4 at max_edge 1: 16 triangles, which cut the shared side
  // x = 0.5 into 4. B's sides are 0.5 <= 1: B stays one patch, patch 0 = face 0 with its own corners. 17 patches
  // (the conforming split gave 20: B cut 1 x 4).
  const PatchSet s = make_patches(mesh, 1.0);
  REQUIRE(s.size() == 17);
  CHECK(s.face[0] == 0);
  for (int k = 0; k < 4; ++k) CHECK(s.corner(0, k) == corner(mesh, 0, k));
  CHECK(s.area[0] == face_area(mesh, 0));
  for (std::size_t p = 1; p < s.size(); ++p) CHECK(s.face[p] == 1);
  check_patching(mesh, s, 1.0, false);
  // The display mesh lists the three T-junction points of T's split in B's polygon (4 + 3 points).
  const DisplayMesh d = make_display_mesh(s);
  CHECK(d.offsets[1] - d.offsets[0] == 7);
  CHECK(d.groups == 1);
  // With them the display polygons are conforming: every polygon edge is used twice or lies on the outline
  // (0.5 + 0.5 + 0.5 + T's two long sides), so the smooth point fields have no crack at the junctions.
  std::map<std::pair<std::int64_t, std::int64_t>, int> edges;
  for (std::size_t i = 0; i + 1 < d.offsets.size(); ++i)
    for (std::int64_t k = d.offsets[i]; k < d.offsets[i + 1]; ++k) {
      const std::int64_t a = d.ids[static_cast<std::size_t>(k)];
      const std::int64_t b = d.ids[static_cast<std::size_t>(k + 1 < d.offsets[i + 1] ? k + 1 : d.offsets[i])];
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  double outline = 0;
  for (const auto& [e, used] : edges) {
    CHECK(used <= 2);
    if (used == 1) outline += (d.points[static_cast<std::size_t>(e.first)] - d.points[static_cast<std::size_t>(e.second)]).norm();
  }
  CHECK(outline == Approx(1.5 + 2 * std::hypot(3.5, 0.25)));
}

TEST_CASE("max_area: no patch above the bound, cells close to square, counts by hand", "[patch]") {
  Mesh mesh;
  mesh.path = "generated";
  // A unit square, a 10 x 1 strip, a right triangle with legs 1, a trapezoid (widths 2 and 1, height 1).
  mesh.vertices = {{0, 0, 0},  {1, 0, 0},  {1, 1, 0},  {0, 1, 0},  {0, 0, 1},    {10, 0, 1}, {10, 1, 1},
                   {0, 1, 1},  {0, 0, 2},  {1, 0, 2},  {0, 1, 2},  {0, 0, 3},    {2, 0, 3},  {1.5, 1, 3},
                   {0.5, 1, 3}};
  mesh.faces = {{0, 1, 2, 3}, {4, 5, 6, 7}, {8, 9, 10, -1}, {11, 12, 13, 14}};
  Material white;
  white.name = "white";
  white.Kd = Rgb(0.5, 0.5, 0.5);
  mesh.materials = {white};
  mesh.face_material = {0, 0, 0, 0};
  validate_mesh(mesh);
  PatchingOptions o;
  o.max_area = 0.1;
  const PatchSet s = make_patches(mesh, o);
  check_patching(mesh, s, 0, true, 0.1);
  std::vector<int> count(4, 0);
  for (std::size_t p = 0; p < s.size(); ++p) ++count[static_cast<std::size_t>(s.face[p])];
  // Square, area 1: 10 cells needed, start floor(sqrt(10)) = 3 x 3 (cells 0.111 > 0.1), one more column: 4 x 3.
  CHECK(count[0] == 12);
  // Strip, area 10: start floor(sqrt(100 * 10)) = 31 x floor(sqrt(100 / 10)) = 3 (cells 0.1075 > 0.1), then one
  // cut across the longer cell side (1/3 > 10/31): 31 x 4, cells 0.0806.
  CHECK(count[1] == 124);
  // Triangle, area 0.5: m = ceil(sqrt(5)) = 3, 9 similar triangles of 0.0556.
  CHECK(count[2] == 9);
  for (std::size_t p = 0; p < s.size(); ++p) {
    if (s.face[p] == 2) CHECK(s.area[p] == Approx(0.5 / 9).epsilon(1e-13));
    // No slivers: every quad cell's sides within a factor 2 of each other (the faces' own aspect is at most 10).
    if (s.is_quad(p) && s.face[p] != 3) {
      const double a = (s.corner(p, 1) - s.corner(p, 0)).norm(), b = (s.corner(p, 3) - s.corner(p, 0)).norm();
      CHECK(std::max(a, b) / std::min(a, b) <= 2.0);
    }
  }
  // Combined with max_edge, both bounds hold; a bound the faces already meet splits nothing.
  o.max_edge = 0.3;
  check_patching(mesh, make_patches(mesh, o), 0.3, true, 0.1);
  PatchingOptions loose;
  loose.max_area = 100;
  loose.max_edge = 100;
  CHECK(make_patches(mesh, loose).size() == 4);
  // Tight bounds on the trapezoid: its cells shrink towards the narrow side, the largest (a corner cell) fits.
  for (const double a : {0.5, 0.05, 0.003}) {
    PatchingOptions t;
    t.max_area = a;
    INFO("max area " << a);
    check_patching(mesh, make_patches(mesh, t), 0, true, a);
  }
}

TEST_CASE("a non-manifold edge is split once for all of its faces", "[patch]") {
  const Mesh mesh = load_scene(data("nonmanifold_edge.obj"));
  const PatchSet s = make_patches(mesh, 0.3);
  CHECK(s.size() == 3 * 16);
  check_patching(mesh, s, 0.3);
}

TEST_CASE("the conformity check detects a crack and a T-junction", "[patch]") {
  const Mesh mesh = load_scene(bundled("perpendicular_squares.obj"));
  const PatchSet good = make_patches(mesh, 0.5);
  REQUIRE(conformity_problems(mesh, good).empty());
  // The midpoint of the shared edge x = y = 0.
  std::int32_t mid = -1;
  for (std::size_t i = 0; i < good.points.size(); ++i)
    if (good.points[i] == Vec3(0, 0, 0.5)) mid = static_cast<std::int32_t>(i);
  REQUIRE(mid >= 0);

  // Crack: one patch of face 1 gets its own copy of the shared midpoint.
  PatchSet crack = good;
  crack.points.push_back(crack.points[static_cast<std::size_t>(mid)]);
  for (std::size_t p = 0; p < crack.size(); ++p)
    if (crack.face[p] == 1)
      for (auto& c : crack.corners[p])
        if (c == mid) {
          c = static_cast<std::int32_t>(crack.points.size() - 1);
          p = crack.size() - 1;
          break;
        }
  CHECK(!conformity_problems(mesh, crack).empty());

  // T-junction: face 1 as one patch next to face 0 split in two along the shared edge.
  PatchSet t = good;
  std::vector<std::size_t> keep;
  for (std::size_t p = 0; p < t.size(); ++p)
    if (t.face[p] == 0) keep.push_back(p);
  auto point_at = [&](const Vec3& q) {
    for (std::size_t i = 0; i < t.points.size(); ++i)
      if (t.points[i] == q) return static_cast<std::int32_t>(i);
    return -1;
  };
  PatchSet joined;
  joined.points = t.points;
  for (std::size_t p : keep) {
    joined.corners.push_back(t.corners[p]);
    joined.face.push_back(0);
  }
  joined.corners.push_back({point_at({0, 0, 0}), point_at({0, 1, 0}), point_at({0, 1, 1}), point_at({0, 0, 1})});
  joined.face.push_back(1);
  joined.area.resize(joined.corners.size());
  CHECK(!conformity_problems(mesh, joined).empty());
}

TEST_CASE("patching refuses a NaN max_edge, an absurd patch count and an unvalidated mesh", "[patch]") {
  const Mesh mesh = load_scene(bundled("cornell_box.obj"));
  CHECK_THROWS_AS(make_patches(mesh, std::nan("")), InputError);
  CHECK_THROWS_WITH(make_patches(mesh, 0.01), Catch::Contains("use a larger max edge"));
  PatchingOptions tiny;
  tiny.max_area = 1e-6;
  CHECK_THROWS_WITH(make_patches(mesh, tiny), Catch::Contains("max area"));
  tiny.max_area = std::nan("");
  CHECK_THROWS_AS(make_patches(mesh, tiny), InputError);
  Mesh raw = read_scene(data("no_material.obj"));  // face_material -1: validate_mesh was skipped
  CHECK_THROWS_WITH(make_patches(raw, 0.0), Catch::Contains("validate the mesh"));
}
