// Repairs of real exporters' faces, all found in one read: faces of fewer than 3 corners, repeated corners
// (consecutive or not, by index or by position), duplicate faces (back to back: one two-sided face; facing the
// same way: one dropped). Each repair keeps the area as drawn to rounding, and --strict refuses each.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "core/error.h"
#include "mesh/face_geometry.h"
#include "mesh/read_obj.h"
#include "mesh/repeated_corners.h"
#include "mesh/validate.h"

using namespace radwalk;

namespace {

const char* kMtl =
    "newmtl light\nKd 0.5 0.5 0.5\nKe 1 1 1\n"
    "newmtl wood\nKd 0.4 0.3 0.2\n"
    "newmtl paint\nKd 0.7 0.7 0.7\n";

MtlSource one_library() {
  return {[](const std::string& path) { return path == "room.mtl"; }, [](const std::string&) { return std::string(kMtl); }};
}

// A lit unit square (face 0) and then `faces`, read and validated; the findings and the refusal ("" if none).
struct Loaded {
  Mesh mesh;
  std::vector<Finding> findings;
  std::string refusal;
};
Loaded load(const std::string& faces, bool strict = false) {
  const std::string obj = "mtllib room.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\nv 0 0 1\n"
                          "v 1 0 1\nv 0 0 1\nusemtl light\nf 1 2 3 4\no chair\ng seat\nusemtl wood\n" +
                          faces;
  ReadOptions read;
  read.strict = strict;
  Loaded out;
  try {
    out.mesh = read_obj_text("room.obj", obj, one_library(), read);
    ValidationTolerances tol;
    tol.strict = strict;
    validate_mesh(out.mesh, tol);
    out.findings = out.mesh.findings;
  } catch (const MeshRefused& e) {
    out.findings = e.findings();
    out.refusal = e.what();
  } catch (const InputError& e) {
    out.refusal = e.what();
  }
  return out;
}

const Finding* first_of(const std::vector<Finding>& findings, const std::string& kind) {
  for (const Finding& f : findings)
    if (f.kind == kind) return &f;
  return nullptr;
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

double total_area(const Mesh& mesh) {
  double a = 0;
  for (std::size_t f = 0; f < mesh.face_count(); ++f) a += face_area(mesh, f);
  return a;
}

}  // namespace

TEST_CASE("an outline is split at its repeated corners into loops", "[mesh][repairs]") {
  CHECK_FALSE(split_repeated_corners({1, 2, 3, 4}).repeated);
  const CornerLoops a = split_repeated_corners({1, 2, 3, 1, 4, 5});
  REQUIRE(a.repeated);
  REQUIRE(a.loops.size() == 2);
  CHECK(a.loops[0] == std::vector<int>{0, 1, 2});
  CHECK(a.loops[1] == std::vector<int>{0, 4, 5});
  const CornerLoops b = split_repeated_corners({1, 2, 2, 3});
  REQUIRE(b.loops.size() == 2);
  CHECK(b.loops[0] == std::vector<int>{1});
  CHECK(b.loops[1] == std::vector<int>{0, 1, 3});
  const CornerLoops c = split_repeated_corners({1, 2, 1});
  REQUIRE(c.loops.size() == 2);
  CHECK(c.loops[0] == std::vector<int>{0, 1});
  CHECK(c.loops[1] == std::vector<int>{0});
}

TEST_CASE("a face of 2 corners is dropped with a warning naming file, line, object and group, and reading goes on",
          "[mesh][repairs]") {
  // f 2 3 (a segment), f 2 3 2 (a spike), then a bad index: all three found in one run.
  const Loaded r = load("f 2 3\nf 2 3 2\nf 2 5 6\nf 1 2 99\n");
  REQUIRE_FALSE(r.refusal.empty());  // the bad index cannot be repaired
  const Finding* two = first_of(r.findings, "face of fewer than 3 corners dropped");
  REQUIRE(two != nullptr);
  CHECK(two->severity == Severity::repair);
  CHECK(two->file == "room.obj");
  CHECK(two->line == 16);
  CHECK(two->object == "chair");
  CHECK(two->group == "seat");
  CHECK(contains(two->message, "area 0"));
  const Finding* spike = first_of(r.findings, "face without area dropped");
  REQUIRE(spike != nullptr);
  CHECK(spike->line == 17);
  CHECK(contains(spike->message, "repeats vertex 2"));
  CHECK(contains(spike->message, "area 0"));
  const Finding* bad = first_of(r.findings, "bad vertex index");
  REQUIRE(bad != nullptr);
  CHECK(bad->line == 19);
  // Without the bad face the scene is accepted, the segment and the spike dropped.
  const Loaded ok = load("f 2 3\nf 2 3 2\nf 2 5 6\n");
  REQUIRE(ok.refusal.empty());
  CHECK(ok.mesh.face_count() == 2);
  // With --strict each is refused, and every refusal is listed.
  const Loaded strict = load("f 2 3\nf 2 3 2\nf 2 5 6\n", true);
  REQUIRE_FALSE(strict.refusal.empty());
  CHECK(first_of(strict.findings, "fewer than 3 corners") != nullptr);
  CHECK(first_of(strict.findings, "repeated corners") != nullptr);
}

TEST_CASE("repeated corners are removed and the area as drawn is kept", "[mesh][repairs]") {
  // Two triangles touching at vertex 2 written as one outline (2 5 6 2 9 8 is 2-5-6 and 2-9-8, the second vertical).
  const Loaded r = load("f 2 5 6 2 8 7\n");
  REQUIRE(r.refusal.empty());
  const Finding* f = first_of(r.findings, "repeated corners removed");
  REQUIRE(f != nullptr);
  CHECK(contains(f->message, "split at its repeats into 2 faces"));
  CHECK(r.mesh.face_count() == 3);
  // lit square 1, triangle 2-5-6 (area 1/2), triangle 2-8-7 (area 1/2).
  CHECK(total_area(r.mesh) == Approx(2.0).epsilon(1e-14));
  // A consecutive repeat in a quad: a triangle of the same area.
  const Loaded q = load("f 2 5 5 6\n");
  REQUIRE(q.refusal.empty());
  CHECK(q.mesh.face_count() == 2);
  CHECK(total_area(q.mesh) == Approx(1.5).epsilon(1e-14));
  // A repeat by position (vertex 9 is vertex 7's point): a triangle 7 8 9 has no area, dropped with its area 0.
  const Loaded w = load("f 2 5 6\nf 7 8 9\n");
  REQUIRE(w.refusal.empty());
  CHECK(w.mesh.face_count() == 2);
  const Finding* d = first_of(w.findings, "face without area dropped");
  REQUIRE(d != nullptr);
  CHECK(d->line == 17);
  CHECK(contains(d->message, "at the same point"));
  CHECK(contains(d->message, "area 0"));
  // A quad with a repeat by position at adjacent corners: a triangle of the quad's area.
  const Loaded t = load("f 2 8 7 9\n");
  REQUIRE(t.refusal.empty());
  CHECK(total_area(t.mesh) == Approx(1.5).epsilon(1e-14));
  CHECK(first_of(t.findings, "repeated vertex repaired") != nullptr);
}

TEST_CASE("back-to-back duplicate faces become one two-sided face, same-way duplicates one face",
          "[mesh][repairs]") {
  const Loaded r = load("f 2 5 6 3\nf 2 3 6 5\n");
  REQUIRE(r.refusal.empty());
  REQUIRE(r.mesh.face_count() == 2);
  const Finding* f = first_of(r.findings, "back-to-back faces made two-sided");
  REQUIRE(f != nullptr);
  CHECK(f->severity == Severity::repair);
  CHECK(f->line == 17);
  CHECK(f->object == "chair");
  const Material& m = r.mesh.materials[static_cast<std::size_t>(r.mesh.face_material[1])];
  CHECK(m.two_sided);
  CHECK(m.name == "wood");
  CHECK((m.Kd == Rgb(0.4, 0.3, 0.2)).all());
  // The original material stays one-sided for its other faces.
  CHECK_FALSE(r.mesh.materials[1].two_sided);
  CHECK(total_area(r.mesh) == Approx(2.0).epsilon(1e-14));  // one face of area 1 with two sides
  const Loaded same = load("f 2 5 6 3\nf 5 6 3 2\n");
  REQUIRE(same.refusal.empty());
  CHECK(same.mesh.face_count() == 2);
  REQUIRE(first_of(same.findings, "duplicate face dropped") != nullptr);
  CHECK(contains(first_of(same.findings, "duplicate face dropped")->message, "area 1"));
  const Loaded strict = load("f 2 5 6 3\nf 2 3 6 5\n", true);
  REQUIRE_FALSE(strict.refusal.empty());
  CHECK(contains(strict.refusal, "duplicate face"));
}

TEST_CASE("a quad whose split leaves a triangle without area is repaired, not refused: the piece is dropped with a "
          "warning", "[mesh][repairs]") {
  // Two faces of Debian's sweethome3d laptop model (blendswap-cc-by/laptop.obj lines 14960 and 17090), moved and
  // scaled by 1/20 into this scene: a concave sliver quad whose corners lie on a line to 5e-8 (neither diagonal
  // splits it into two triangles turning its way) and a quad whose corners 2 and 3 are 2.5e-9 apart (its split
  // leaves a triangle of area 2.7e-17, below 1e-10 x the squared scene diagonal). Validation used to refuse both
  // while its message said "otherwise dropped" / "otherwise split".
  const std::string faces =
      "v 0.060561750 0.040111000 0.503866400\nv 0.060561800 0.040111000 0.503866400\n"
      "v 0.060561750 0.040111000 0.606483350\nv 0.060561750 0.040111000 0.623586150\n"
      "v -0.003133000 0.000884950 0.041335550\nv -0.004722200 0.001189150 0.040156500\n"
      "v 0.006097050 0.000783500 0.040026200\nv 0.006097000 0.000783500 0.040026200\n"
      "f 10 11 12 13\nf 14 15 16 17\n";
  const Loaded before = load("");
  const Loaded r = load(faces);
  INFO(r.refusal);
  REQUIRE(r.refusal.empty());
  const Finding* dropped = first_of(r.findings, "zero-area face dropped");
  REQUIRE(dropped != nullptr);
  CHECK(contains(dropped->message, "degenerate piece dropped"));
  // The area as drawn is kept to the dropped pieces' area (below 1e-10 x the squared scene diagonal, about 6e-10).
  const double drawn = total_area(r.mesh) - total_area(before.mesh);
  CHECK(drawn > 0);
  CHECK(drawn < 1e-5);
  // With --strict both are refused, and the message says so.
  const Loaded strict = load(faces, true);
  CHECK(!strict.refusal.empty());
}
