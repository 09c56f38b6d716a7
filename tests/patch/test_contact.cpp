// Contacts: an object standing on a face is found, its footprint is the polygon of its bottom edges, and the
// supporting face is cut along it into pieces that tile it, each either under the object or beside it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/rng.h"
#include "mesh/face_geometry.h"
#include "mesh/read_scene.h"
#include "mesh/validate.h"
#include "patch/contact.h"
#include "patch/contact_patches.h"
#include "patch/patching.h"

using namespace radwalk;

namespace {

std::string bundled(const std::string& name) { return std::string(RADWALK_SOURCE_DIR) + "/meshes/" + name; }

const Vec3& corner(const Mesh& m, std::size_t f, int k) {
  return m.vertices[static_cast<std::size_t>(m.faces[f][static_cast<std::size_t>(k)])];
}

// Shoelace area of a polygon's projection on y = 0 (x, z).
double area_xz(const std::vector<Vec3>& p) {
  double a = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    const Vec3& u = p[k];
    const Vec3& v = p[(k + 1) % p.size()];
    a += u.z() * v.x() - u.x() * v.z();
  }
  return 0.5 * std::abs(a);
}

// Signed distance of q to the inside of convex polygon K (counter-clockwise about n): >= 0 inside, by edge lines.
double inside_margin(const std::vector<Vec3>& K, const Vec3& n, const Vec3& q) {
  double m = 1e300;
  for (std::size_t k = 0; k < K.size(); ++k) {
    const Vec3 d = n.cross(K[(k + 1) % K.size()] - K[k]).normalized();
    m = std::min(m, (q - K[k]).dot(d));
  }
  return m;
}

// (Vector area of polygon p) . n: positive when p turns counter-clockwise about n.
double vector_area_dot(const std::vector<Vec3>& p, const Vec3& n) {
  Vec3 a = Vec3::Zero();
  for (std::size_t k = 0; k + 2 < p.size(); ++k) a += 0.5 * (p[k + 1] - p[0]).cross(p[k + 2] - p[0]);
  return a.dot(n);
}

// Checks the cut: the pieces of each input face keep its orientation and material, add up to its area, and each
// piece lies entirely inside or entirely outside every convex footprint on its plane.
void check_cut(const Mesh& before, const Mesh& after, const std::vector<Contact>& contacts, double tol) {
  std::vector<double> area(before.face_count(), 0.0);
  for (std::size_t f = 0; f < after.face_count(); ++f) {
    const auto s = static_cast<std::size_t>(after.source_face(f));
    REQUIRE(s < before.face_count());
    CHECK(after.face_material[f] == before.face_material[s]);
    CHECK(face_vector_area(after, f).dot(face_vector_area(before, s)) > 0);
    area[s] += face_area(after, f);
    for (const Contact& c : contacts) {
      if (std::find(c.supports.begin(), c.supports.end(), static_cast<std::int32_t>(s)) == c.supports.end()) continue;
      const Vec3 n = face_vector_area(before, s).normalized();
      double lo = 1e300, hi = -1e300;
      for (int k = 0; k < after.corner_count(f); ++k) {
        const double m = inside_margin(c.footprint, n, corner(after, f, k));
        lo = std::min(lo, m);
        hi = std::max(hi, m);
      }
      INFO("piece " << f << " of face " << s << ": footprint margins " << lo << " .. " << hi);
      CHECK((lo >= -tol || hi <= tol));  // inside or outside, never across
    }
  }
  for (std::size_t s = 0; s < before.face_count(); ++s) {
    INFO("face " << s);
    CHECK(area[s] == Approx(face_area(before, s)).epsilon(1e-12));
  }
}

// A 4 x 4 floor (one quad, facing up) with a unit block standing on [1, 2] x [1, 2] (4 sides facing out, a top,
// optionally a bottom facing down), optionally inside walls facing in.
Mesh block_on_floor(bool bottom, bool walls, bool plate = false) {
  Mesh m;
  m.path = "generated";
  auto v = [&](double x, double y, double z) {
    m.vertices.push_back({x, y, z});
    return static_cast<std::int32_t>(m.vertices.size() - 1);
  };
  auto quad = [&](std::int32_t a, std::int32_t b, std::int32_t c, std::int32_t d) { m.faces.push_back({a, b, c, d}); };
  // Floor, normal +y: corners counter-clockwise seen from above.
  const auto f0 = v(0, 0, 0), f1 = v(0, 0, 4), f2 = v(4, 0, 4), f3 = v(4, 0, 0);
  quad(f0, f1, f2, f3);
  // Block: bottom corners b, top corners t.
  const auto b0 = v(1, 0, 1), b1 = v(2, 0, 1), b2 = v(2, 0, 2), b3 = v(1, 0, 2);
  const auto t0 = v(1, 1, 1), t1 = v(2, 1, 1), t2 = v(2, 1, 2), t3 = v(1, 1, 2);
  quad(b1, b0, t0, t1);  // z = 1, normal -z
  quad(b2, b1, t1, t2);  // x = 2, normal +x
  quad(b3, b2, t2, t3);  // z = 2, normal +z
  quad(b0, b3, t3, t0);  // x = 1, normal -x
  quad(t0, t1, t2, t3);  // top: normal +y? (t1 - t0) x (t3 - t0) = x x z = -y: reversed below
  std::swap(m.faces.back()[1], m.faces.back()[3]);
  if (bottom) quad(b0, b1, b2, b3);  // (x) x (z) = -y: facing down, onto the floor
  if (walls) {
    const auto w0 = v(0, 2, 0), w1 = v(0, 2, 4), w2 = v(4, 2, 4), w3 = v(4, 2, 0);
    quad(f0, w0, w1, f1);  // x = 0, facing in (+x)
    quad(f1, w1, w2, f2);
    quad(f2, w2, w3, f3);
    quad(f3, w3, w0, f0);
  }
  if (plate) {  // a thin plate lying on the floor at [2.5, 3.5] x [2.5, 3], facing down
    const auto p0 = v(2.5, 0, 2.5), p1 = v(3.5, 0, 2.5), p2 = v(3.5, 0, 3), p3 = v(2.5, 0, 3);
    quad(p0, p1, p2, p3);
  }
  Material white;
  white.name = "white";
  white.Kd = Rgb(0.5, 0.5, 0.5);
  m.materials = {white};
  m.face_material.assign(m.faces.size(), 0);
  validate_mesh(m);
  return m;
}

}  // namespace

TEST_CASE("contacts: a block on a floor is found and the floor cut into the footprint and 4 pieces", "[patch][contact]") {
  for (const bool bottom : {false, true}) {
    INFO("block bottom " << bottom);
    const Mesh m = block_on_floor(bottom, false);
    const auto contacts = find_contacts(m);
    REQUIRE(contacts.size() == 1);  // with a bottom: the same footprint, not a second contact
    const Contact& c = contacts[0];
    CHECK(c.convex);
    CHECK_FALSE(c.lying);
    CHECK(c.footprint.size() == 4);
    CHECK(c.area == Approx(1.0).epsilon(1e-14));
    CHECK(c.supports == std::vector<std::int32_t>{0});
    CHECK(c.standing == std::vector<std::int32_t>{1, 2, 3, 4});
    CHECK_THAT(describe_contact(m, c), Catch::Contains("faces 1, 2, 3, 4") && Catch::Contains("stand on face 0") &&
                                           Catch::Contains("material 'white'"));
    std::size_t cut = 0;
    const Mesh after = cut_along_contacts(m, contacts, &cut);
    CHECK(cut == 1);
    // The footprint first, then the pinwheel's four arms, each beyond one footprint edge and bounded by that
    // edge's line and the neighbouring edge's line continued beyond one corner (by hand, on [0, 4]^2 about
    // [1, 2]^2, every arm a rectangle: 1 x 2, 3 x 1, 2 x 2 and 2 x 3, whichever way the pinwheel turns; the former
    // cut along whole chords gave strips of 8, 4, 2, 1).
    REQUIRE(after.face_count() == m.face_count() + 4);
    CHECK(face_area(after, 0) == Approx(1.0));
    std::vector<double> arms;
    for (std::size_t f = 1; f <= 4; ++f) arms.push_back(face_area(after, f));
    std::sort(arms.begin(), arms.end());
    CHECK(arms == std::vector<double>{2, 3, 4, 6});
    for (std::size_t f = 0; f < 5; ++f) CHECK(after.source_face(f) == 0);
    for (std::size_t f = 5; f < after.face_count(); ++f) CHECK(after.source_face(f) == static_cast<long>(f - 4));
    check_cut(m, after, contacts, 1e-12);
    // The patches then split each piece on its own: areas still add up per input face.
    const PatchSet s = make_patches(after, 0.5);
    double floor_area = 0;
    for (std::size_t p = 0; p < s.size(); ++p)
      if (s.face[p] == 0) floor_area += s.area[p];
    CHECK(floor_area == Approx(16.0).epsilon(1e-12));
  }
}

TEST_CASE("contacts: walls around a floor are no contact, a plate lying on it is one", "[patch][contact]") {
  const Mesh m = block_on_floor(false, true, true);
  const auto contacts = find_contacts(m);
  REQUIRE(contacts.size() == 2);
  CHECK_FALSE(contacts[0].lying);
  CHECK(contacts[1].lying);
  CHECK(contacts[1].standing == std::vector<std::int32_t>{10});
  CHECK(contacts[1].area == Approx(0.5));
  CHECK_THAT(describe_contact(m, contacts[1]), Catch::Contains("lies back to back on face 0"));
  const Mesh after = cut_along_contacts(m, contacts);
  check_cut(m, after, contacts, 1e-12);
  double floor_area = 0;
  std::size_t pieces = 0;
  for (std::size_t f = 0; f < after.face_count(); ++f)
    if (after.source_face(f) == 0) {
      floor_area += face_area(after, f);
      ++pieces;
    }
  CHECK(floor_area == Approx(16.0));
  CHECK(pieces == 5 + 4);  // the block's cut (5 pieces), then the plate's footprint cuts one of them (4 more)
}

TEST_CASE("contacts: the Cornell box's blocks stand on the floor, cut along their footprints", "[patch][contact]") {
  const Mesh m = load_scene(bundled("cornell_box.obj"));
  const auto contacts = find_contacts(m);
  REQUIRE(contacts.size() == 2);
  // The footprints are the blocks' bottom corners (meshes/cornell_box.obj, lines v 130 0 65 ... and v 423 0 247
  // ...), by the shoelace formula: short block 27633 mm^2, tall block 27626.5 mm^2.
  CHECK(contacts[0].area == Approx(area_xz({{290, 0, 114}, {240, 0, 272}, {82, 0, 225}, {130, 0, 65}})));
  CHECK(contacts[1].area == Approx(area_xz({{423, 0, 247}, {472, 0, 406}, {314, 0, 456}, {265, 0, 296}})));
  for (const Contact& c : contacts) {
    CHECK(c.convex);
    CHECK(c.standing.size() == 4);
    for (const std::int32_t f : c.supports) CHECK(f <= 8);  // floor faces 0-8
  }
  std::size_t cut = 0;
  const Mesh after = cut_along_contacts(m, contacts, &cut);
  CHECK(cut == 7);
  check_cut(m, after, contacts, 1e-9);
  // Under the blocks the pieces add up to the footprints.
  for (const Contact& c : contacts) {
    double under = 0;
    const Vec3 up(0, 1, 0);
    for (std::size_t f = 0; f < after.face_count(); ++f) {
      if (after.source_face(f) > 8) continue;
      Vec3 centre = Vec3::Zero();
      for (int k = 0; k < after.corner_count(f); ++k) centre += corner(after, f, k) / after.corner_count(f);
      if (inside_margin(c.footprint, up, centre) > 0) under += face_area(after, f);
    }
    CHECK(under == Approx(c.area).epsilon(1e-9));
  }
}

// The smallest corner angle of face f (radians).
double smallest_angle(const Mesh& m, std::size_t f) {
  double smallest = kPi;
  const int n = m.corner_count(f);
  for (int k = 0; k < n; ++k) {
    const Vec3 u = corner(m, f, (k + n - 1) % n) - corner(m, f, k), v = corner(m, f, (k + 1) % n) - corner(m, f, k);
    smallest = std::min(smallest, std::atan2(u.cross(v).norm(), u.dot(v)));
  }
  return smallest;
}

TEST_CASE("contacts: the Cornell box's floor is cut into pieces without slivers, the footprints exact",
          "[patch][contact]") {
  // The floor is nine input faces (a 3 x 3 grid) and the blocks' footprints are rotated by about 17 degrees, so
  // every piece beside a footprint has angles of about 17, 73 or 107 degrees where a footprint edge's line meets a
  // floor face's side. The smallest angle the geometry forces is 16.6 degrees: the short block's edge
  // (82, 225) -> (240, 272) crosses the floor faces' side z = 227 at atan(47 / 158). The former cut, along whole
  // chords and each piece fanned from its first corner, left a 0.6-degree sliver of 285 mm^2 (split into four
  // 71 mm^2 slivers at --max-edge 200) and an 11 mm^2 triangle where a chord ran on beyond the footprint's
  // neighbourhood; it fails both checks below (smallest angle 0.6 degrees, 35 pieces).
  const Mesh m = load_scene(bundled("cornell_box.obj"));
  const auto contacts = find_contacts(m);
  const Mesh after = cut_along_contacts(m, contacts);
  check_cut(m, after, contacts, 1e-9);
  double smallest = kPi;
  std::size_t floor_pieces = 0;
  for (std::size_t f = 0; f < after.face_count(); ++f) {
    if (after.source_face(f) > 8) continue;
    ++floor_pieces;
    INFO("piece " << f << " of face " << after.source_face(f) << ": area " << face_area(after, f));
    CHECK(smallest_angle(after, f) >= 16.5 * kPi / 180);
    smallest = std::min(smallest, smallest_angle(after, f));
  }
  CHECK(smallest == Approx(std::atan2(47.0, 158.0)).epsilon(1e-2));
  // The nine faces: 2 uncut, the 7 cut ones into 28 pieces, 2 + 28 = 30 (1, 3, 5, 3, 8, 3, 3, 3, 1 by face;
  // at most one arm per footprint edge and the part under the footprint, per footprint on the face).
  CHECK(floor_pieces == 30);
}

TEST_CASE("contacts: random convex footprints across a floor's faces cut it into convex pieces that tile it",
          "[patch][contact]") {
  // A floor [0, 4]^2 (normal +y) of four faces: three quads and a quad cut into two triangles along a diagonal. Each
  // trial puts one convex footprint anywhere (3 to 6 corners on a circle of radius 0.2 to 1.2, so it may reach
  // beyond a face or the floor), or two disjoint ones, one each side of x = 2. Whichever way each pinwheel turns,
  // its arms and the part under the footprint must tile every face (areas add up), lie inside or outside every
  // footprint, and be convex with positive area (make_patches splits a quad bilinearly).
  Mesh m;
  m.path = "generated";
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 2; ++i) m.vertices.push_back({2.0 * i, 0, 2.0 * j});
  auto at = [](int i, int j) { return static_cast<std::int32_t>(3 * j + i); };
  m.faces.push_back({at(0, 0), at(0, 1), at(1, 1), at(1, 0)});  // (z) x (x) = +y
  m.faces.push_back({at(1, 0), at(1, 1), at(2, 1), at(2, 0)});
  m.faces.push_back({at(0, 1), at(0, 2), at(1, 2), at(1, 1)});
  m.faces.push_back({at(1, 1), at(1, 2), at(2, 2), -1});
  m.faces.push_back({at(1, 1), at(2, 2), at(2, 1), -1});
  Material white;
  white.name = "white";
  white.Kd = Rgb(0.5, 0.5, 0.5);
  m.materials = {white};
  m.face_material.assign(m.faces.size(), 0);
  validate_mesh(m);
  const Vec3 up(0, 1, 0);
  auto footprint = [&](Rng& rng, double x_lo, double x_hi) {
    const int corners = 3 + static_cast<int>(rng.uniform_index(4));
    const double r = 0.2 + (std::min(1.2, 0.5 * (x_hi - x_lo)) - 0.2) * rng.uniform();
    const double cx = x_lo + r + (x_hi - x_lo - 2 * r) * rng.uniform(), cz = 0.5 + 3 * rng.uniform();
    std::vector<double> angle;
    for (int k = 0; k < corners; ++k) angle.push_back(2 * kPi * rng.uniform());
    std::sort(angle.begin(), angle.end());
    Contact c;
    for (const double a : angle) c.footprint.push_back({cx + r * std::cos(a), 0, cz + r * std::sin(a)});
    // Counter-clockwise about +y: the corners by increasing angle in (x, z) turn about -y, so reversed.
    std::reverse(c.footprint.begin(), c.footprint.end());
    c.supports = {0, 1, 2, 3, 4};  // a face the footprint misses keeps its one piece
    return c;
  };
  Rng rng = stream(7, StreamDomain::test, 41, 0);
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<Contact> contacts;
    if (trial % 2 == 0) {
      contacts.push_back(footprint(rng, -0.5, 4.5));
    } else {
      contacts.push_back(footprint(rng, 0, 2));
      contacts.push_back(footprint(rng, 2, 4));
    }
    INFO("trial " << trial);
    for (const Contact& c : contacts) REQUIRE(vector_area_dot(c.footprint, up) > 0);
    const Mesh after = cut_along_contacts(m, contacts);
    check_cut(m, after, contacts, 1e-9);
    for (std::size_t f = 0; f < after.face_count(); ++f) {
      INFO("piece " << f << " of face " << after.source_face(f));
      CHECK(face_area(after, f) > 0);
      const int n = after.corner_count(f);
      for (int k = 0; k < n; ++k) {
        const Vec3 &a = corner(after, f, k), &b = corner(after, f, (k + 1) % n), &c = corner(after, f, (k + 2) % n);
        CHECK((b - a).cross(c - b).dot(up) >= -1e-12);
      }
    }
    // No two vertices of the pieces at one place (within 1e-9 of the extent): the same corner computed by two
    // pieces in a different order is one vertex, or a cell gets two coincident corners no reader can triangulate.
    std::size_t coincident = 0;
    for (std::size_t a = m.vertices.size(); a < after.vertices.size(); ++a)
      for (std::size_t b = 0; b < a; ++b)
        if ((after.vertices[a] - after.vertices[b]).norm() <= 1e-9 * 5) ++coincident;
    CHECK(coincident == 0);
  }
}

namespace {

// A shelf's side panel: the plane z = 0 (facing +z), [0, 1] x [0, 2] as one quad, with `boards` thin boards (one
// quad each, zero thickness) standing on it at y = 2 (k + 1) / (boards + 1), their edges x in [0, 1] lying on it.
// With `along_edge`, one more board stands on the panel's edge y = 0, which is no contact line across it.
Mesh panel_with_boards(int boards, bool along_edge = false) {
  Mesh m;
  m.path = "generated";
  auto v = [&](double x, double y, double z) {
    m.vertices.push_back({x, y, z});
    return static_cast<std::int32_t>(m.vertices.size() - 1);
  };
  m.faces.push_back({v(0, 0, 0), v(1, 0, 0), v(1, 2, 0), v(0, 2, 0)});  // (x) x (y) = +z
  auto board = [&](double y) { m.faces.push_back({v(0, y, 0), v(0, y, 1), v(1, y, 1), v(1, y, 0)}); };
  for (int k = 0; k < boards; ++k) board(2.0 * (k + 1) / (boards + 1));
  if (along_edge) board(0);
  Material wood;
  wood.name = "wood";
  wood.Kd = Rgb(0.5, 0.5, 0.5);
  m.materials = {wood};
  m.face_material.assign(m.faces.size(), 0);
  validate_mesh(m);
  return m;
}

}  // namespace

TEST_CASE("contacts: a board's edge touching a panel is a contact line, and the panel is cut along it",
          "[patch][contact]") {
  // Three boards: three lines, the panel cut into the four compartments, 0.5 x 1 each, in order of y.
  const Mesh m = panel_with_boards(3, true);
  const auto contacts = find_contacts(m);
  REQUIRE(contacts.size() == 3);  // the board on the panel's edge crosses no interior: no line
  for (std::size_t k = 0; k < 3; ++k) {
    const Contact& c = contacts[k];
    CHECK(c.line);
    CHECK(c.convex);
    CHECK(c.area == 0);
    CHECK(c.supports == std::vector<std::int32_t>{0});
    CHECK(c.standing == std::vector<std::int32_t>{static_cast<std::int32_t>(k + 1)});
    REQUIRE(c.footprint.size() == 2);
    CHECK(c.footprint[0].y() == Approx(0.5 * (k + 1)));
    CHECK(c.footprint[1].y() == Approx(0.5 * (k + 1)));
    CHECK_THAT(describe_contact(m, c), Catch::Contains("touches face 0") && Catch::Contains("along a line of length 1"));
  }
  std::size_t cut = 0;
  const Mesh after = cut_along_contacts(m, contacts, &cut);
  CHECK(cut == 1);
  std::vector<std::pair<double, double>> compartments;  // (lowest y, highest y) of each piece of the panel
  double total = 0;
  for (std::size_t f = 0; f < after.face_count(); ++f) {
    if (after.source_face(f) != 0) continue;
    double lo = 1e300, hi = -1e300;
    for (int k = 0; k < after.corner_count(f); ++k) {
      lo = std::min(lo, corner(after, f, k).y());
      hi = std::max(hi, corner(after, f, k).y());
      CHECK(corner(after, f, k).z() == 0);
    }
    compartments.emplace_back(lo, hi);
    total += face_area(after, f);
    CHECK(face_vector_area(after, f).z() > 0);
  }
  std::sort(compartments.begin(), compartments.end());
  REQUIRE(compartments.size() == 4);
  for (std::size_t k = 0; k < 4; ++k) {
    CHECK(compartments[k].first == Approx(0.5 * k).margin(1e-15));
    CHECK(compartments[k].second == Approx(0.5 * (k + 1)));
  }
  CHECK(total == Approx(2.0).epsilon(1e-14));
}

TEST_CASE("contacts: a face is cut along at most kMaxContactLinesPerFace lines, the others reported",
          "[patch][contact]") {
  const int boards = kMaxContactLinesPerFace + 3;
  const Mesh m = panel_with_boards(boards);
  const auto contacts = find_contacts(m);
  REQUIRE(contacts.size() == static_cast<std::size_t>(boards));
  const auto cut_lines = std::count_if(contacts.begin(), contacts.end(), [](const Contact& c) { return c.convex; });
  CHECK(cut_lines == kMaxContactLinesPerFace);
  const auto reported = std::find_if(contacts.begin(), contacts.end(), [](const Contact& c) { return !c.convex; });
  REQUIRE(reported != contacts.end());
  CHECK_THAT(describe_contact(m, *reported), Catch::Contains("not cut"));
  std::size_t pieces = 0;
  const Mesh after = cut_along_contacts(m, contacts);
  for (std::size_t f = 0; f < after.face_count(); ++f) pieces += after.source_face(f) == 0;
  CHECK(pieces == static_cast<std::size_t>(kMaxContactLinesPerFace + 1));
}

namespace {

double contact_area(const std::vector<ContactRegion>& regions, const PatchSet& patches) {
  const std::vector<bool> in = contact_patches(regions, patches);
  double a = 0;
  for (std::size_t i = 0; i < patches.size(); ++i)
    if (in[i]) a += patches.area[i];
  return a;
}

}  // namespace

TEST_CASE("contact patches: the floor under a block and the block's bottom, cut or not, also from contacts found "
          "on the cut mesh", "[patch][contact]") {
  // The unit block with its bottom on the 4 x 4 floor, 0.5 m patches: the floor's four patches under it and the
  // bottom's four, 2 m^2; the same after the cut along the footprint (regions taken before the cut).
  const Mesh m = block_on_floor(true, false);
  const auto contacts = find_contacts(m);
  const auto regions = contact_regions(m, contacts);
  CHECK(contact_area(regions, make_patches(m, 0.5)) == Approx(2.0).epsilon(1e-12));
  CHECK(contact_area(regions, make_patches(cut_along_contacts(m, contacts), 0.5)) == Approx(2.0).epsilon(1e-12));
  // Contacts found again on the cut mesh (what `radwalk exchange` did): the floor's piece under the block is itself a
  // face lying back to back on the bottom, and its input face is the whole floor, which marking a lying face whole
  // by its input face made contact (16 m^2). By the regions' rule only the piece and the bottom touch.
  const Mesh cut = cut_along_contacts(m, contacts);
  const auto again = find_contacts(cut);
  std::string found;
  for (const Contact& c : again) found += describe_contact(cut, c) + (c.lying ? " (lying); " : "; ");
  INFO(found);
  CHECK(std::any_of(again.begin(), again.end(), [&](const Contact& c) {
    return c.lying && c.standing.size() == 1 && cut.source_face(std::size_t(c.standing[0])) == 0;
  }));
  CHECK(contact_area(contact_regions(cut, again), make_patches(cut, 0.5)) == Approx(2.0).epsilon(1e-12));
}

TEST_CASE("contact patches: under an object without a bottom the floor is in contact with nothing",
          "[patch][contact]") {
  // The same block open below (sides and top only): its inside sees the floor under it, which radiates as any face
  // (a cabinet open below, whose floor part an `exchange --contact-faces exclude` held at J = 0 as if touched, so
  // that the cabinet's inside read 140 K). The footprint is still found and cut along; no patch is in contact.
  const Mesh m = block_on_floor(false, false);
  const auto contacts = find_contacts(m);
  REQUIRE(!contacts.empty());
  const auto regions = contact_regions(m, contacts);
  REQUIRE(!regions.empty());
  CHECK(contact_area(regions, make_patches(m, 0.5)) == 0.0);
  CHECK(contact_area(regions, make_patches(cut_along_contacts(m, contacts), 0.5)) == 0.0);
}

TEST_CASE("contact patches: a hundred blocks on a floor, each region's patches found near its footprint",
          "[patch][contact]") {
  // A 20 x 20 floor with 10 x 10 unit blocks (bottoms included) at [2i + 0.5, 2i + 1.5] x [2j + 0.5, 2j + 1.5],
  // 0.5 m patches: exactly the floor's patches under the blocks and the bottoms' patches are in contact, 2 m^2 a
  // block. The regions' patches come from a grid of the centroids: a patch outside every footprint's box is never
  // tested, one inside is.
  Mesh m;
  m.path = "generated";
  auto v = [&](double x, double y, double z) {
    m.vertices.push_back({x, y, z});
    return static_cast<std::int32_t>(m.vertices.size() - 1);
  };
  auto quad = [&](std::int32_t a, std::int32_t b, std::int32_t c, std::int32_t d) { m.faces.push_back({a, b, c, d}); };
  quad(v(0, 0, 0), v(0, 0, 20), v(20, 0, 20), v(20, 0, 0));  // normal +y
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) {
      const double x0 = 2 * i + 0.5, x1 = x0 + 1, z0 = 2 * j + 0.5, z1 = z0 + 1;
      const auto b0 = v(x0, 0, z0), b1 = v(x1, 0, z0), b2 = v(x1, 0, z1), b3 = v(x0, 0, z1);
      const auto t0 = v(x0, 1, z0), t1 = v(x1, 1, z0), t2 = v(x1, 1, z1), t3 = v(x0, 1, z1);
      quad(b1, b0, t0, t1);
      quad(b2, b1, t1, t2);
      quad(b3, b2, t2, t3);
      quad(b0, b3, t3, t0);
      quad(t0, t3, t2, t1);
      quad(b0, b1, b2, b3);  // the bottom, facing down
    }
  Material white;
  white.name = "white";
  white.Kd = Rgb(0.5, 0.5, 0.5);
  m.materials = {white};
  m.face_material.assign(m.faces.size(), 0);
  validate_mesh(m);
  const auto contacts = find_contacts(m);
  const auto regions = contact_regions(m, contacts);
  REQUIRE(regions.size() == 100);
  for (const bool cut : {false, true}) {
    INFO("cut " << cut);
    const PatchSet patches = make_patches(cut ? cut_along_contacts(m, contacts) : m, 0.5);
    const std::vector<bool> in = contact_patches(regions, patches);
    std::size_t expected = 0, wrong = 0;
    for (std::size_t i = 0; i < patches.size(); ++i) {
      const Vec3& x = patches.centroid[i];
      const double u = std::fmod(x.x(), 2.0), w = std::fmod(x.z(), 2.0);
      const bool under = std::abs(x.y()) < 1e-12 && u > 0.5 && u < 1.5 && w > 0.5 && w < 1.5;
      expected += under;
      wrong += in[i] != under;
    }
    CHECK(expected == 100 * 2 * 4);  // per block: the floor's 4 patches under it and the bottom's 4
    CHECK(wrong == 0);
  }
}
