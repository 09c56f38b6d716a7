// An OBJ radwalk wrote (io/obj_writer.h) read back by radwalk's OBJ reader (mesh/read_obj.h): a contact pair (a
// floor piece and the bottom lying on it, patch/contact_pairs.h) reads back as its two one-sided faces from
// radwalk's file, named by its "# radwalk_contact_pair" lines; the same faces in another program's file (without
// radwalk's first line) are still one two-sided face, and a declaration that names no two faces is not used.
// Its faces read back facing as written (its "# radwalk_as_written" line): a cut floor piece that closes a
// bottomless box's shell is not turned by the default orientation, unless an orientation is asked for.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/obj_writer.h"
#include "mesh/read_obj.h"
#include "mesh/validate.h"
#include "patch/patch_builder.h"

using namespace radwalk;

namespace {

std::string temp_path(const std::string& name) { return (std::filesystem::temp_directory_path() / name).string(); }

std::string text_of(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

std::size_t count_of(const Mesh& m, const std::string& kind) {
  std::size_t n = 0;
  for (const Finding& f : m.findings) n += f.kind == kind;
  return n;
}

// A floor of two quads facing up, a box's bottom lying on the first back to back (its corners starting elsewhere),
// the box's side rising from it, a lamp, and a triangle lying on a triangle back to back: patches 0 and 2, and 5
// and 6, are contact pairs.
PatchSet floors_under_boxes() {
  PatchBuilder b;
  const int floor = b.add_material("floor", Rgb(0.7, 0.6, 0.5));
  const int box = b.add_material("box", Rgb(0.2, 0.3, 0.4));
  const int lamp = b.add_material("lamp", Rgb::Zero(), Rgb::Constant(1));
  b.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, floor);
  b.add_quad({1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, floor);
  b.add_quad({1, 1, 0}, {1, 0, 0}, {0, 0, 0}, {0, 1, 0}, box);
  b.add_quad({0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}, box);
  b.add_quad({0, 0, 3}, {0, 1, 3}, {1, 1, 3}, {1, 0, 3}, lamp);
  b.add_triangle({5, 0, 0}, {6, 0, 0}, {5, 1, 0}, floor);
  b.add_triangle({5, 0, 0}, {5, 1, 0}, {6, 0, 0}, box);
  return b.build();
}

// A bottomless box standing on the floor piece cut under it (as the contact cut leaves it: the piece facing up,
// into the box) and a lamp above: the piece closes the box's shell, so orienting the shells outward would turn
// it to face down (out of the box), where the run that made the patches had oriented the floor before the cut.
PatchSet bottomless_box_on_its_floor_piece() {
  PatchBuilder b;
  const int floor = b.add_material("floor", Rgb(0.7, 0.6, 0.5));
  const int box = b.add_material("box", Rgb(0.2, 0.3, 0.4));
  const int lamp = b.add_material("lamp", Rgb::Zero(), Rgb::Constant(1));
  b.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, floor);  // the floor piece, facing up
  b.add_quad({0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}, box);    // the box's sides and top, facing out
  b.add_quad({1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}, box);
  b.add_quad({1, 1, 0}, {0, 1, 0}, {0, 1, 1}, {1, 1, 1}, box);
  b.add_quad({0, 1, 0}, {0, 0, 0}, {0, 0, 1}, {0, 1, 1}, box);
  b.add_quad({0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}, box);
  b.add_quad({0, 0, 3}, {0, 1, 3}, {1, 1, 3}, {1, 0, 3}, lamp);
  return b.build();
}

// Whether mesh face f has patch i's corners in the same order (the same position of each corner: facing the same
// way), its first corner first.
bool same_corners(const Mesh& m, std::size_t f, const PatchSet& patches, std::size_t i) {
  if (m.corner_count(f) != patches.corner_count(i)) return false;
  for (int k = 0; k < patches.corner_count(i); ++k)
    if (m.vertices[static_cast<std::size_t>(m.faces[f][static_cast<std::size_t>(k)])] != patches.corner(i, k))
      return false;
  return true;
}

}  // namespace

TEST_CASE("obj reader: the faces of an OBJ radwalk wrote read back facing as written", "[io][obj][orient]") {
  const PatchSet patches = bottomless_box_on_its_floor_piece();
  const std::string path = temp_path("radwalk_as_written.obj");
  write_obj(path, patches);
  const std::string text = text_of(path);
  REQUIRE(text.find("\n# radwalk_as_written") != std::string::npos);

  // The default: every face as written, nothing flipped, no note.
  {
    Mesh back = read_obj(path);
    REQUIRE(back.as_written);
    validate_mesh(back);
    REQUIRE(back.face_count() == patches.size());
    for (std::size_t i = 0; i < patches.size(); ++i) {
      INFO("patch " << i);
      REQUIRE(same_corners(back, i, patches, i));
    }
    REQUIRE(count_of(back, "faces flipped") == 0);
    REQUIRE(count_of(back, "faces as written oriented again") == 0);
  }
  // The same faces in another program's file (radwalk's first line replaced), or without the as-written line:
  // the orientation is derived again and the floor piece turned down (the control: the scene is one that
  // re-orienting changes).
  const std::string other = temp_path("radwalk_as_written_other.obj");
  std::string without_line = text;
  without_line.erase(without_line.find("# radwalk_as_written"),
                     without_line.find('\n', without_line.find("# radwalk_as_written")) -
                         without_line.find("# radwalk_as_written") + 1);
  for (const std::string& edited : {"# exported by another program" + text.substr(text.find('\n')), without_line}) {
    write_text(other, edited);
    Mesh back = read_obj(other);
    REQUIRE_FALSE(back.as_written);
    validate_mesh(back);
    REQUIRE(back.face_count() == patches.size());
    CHECK_FALSE(same_corners(back, 0, patches, 0));
    for (std::size_t i = 1; i < patches.size(); ++i) CHECK(same_corners(back, i, patches, i));
    CHECK(count_of(back, "faces flipped") == 1);
  }
  // An orientation asked for (--orient outward given) applies to radwalk's file too, with a note saying so;
  // --orient none given keeps the faces with no note.
  for (const OrientMode mode : {OrientMode::outward, OrientMode::consistent, OrientMode::none}) {
    INFO(orient_mode_name(mode));
    Mesh back = read_obj(path);
    ValidationTolerances tol;
    tol.orient = mode;
    tol.orient_given = true;
    validate_mesh(back, tol);
    CHECK(same_corners(back, 0, patches, 0) == (mode == OrientMode::none));
    CHECK(count_of(back, "faces as written oriented again") == (mode == OrientMode::none ? 0u : 1u));
  }
  std::filesystem::remove(path);
  std::filesystem::remove(other);
  std::filesystem::remove(std::filesystem::path(path).replace_extension(".mtl"));
}

TEST_CASE("obj reader: a contact pair radwalk wrote reads back as its two one-sided faces", "[io][obj][contact]") {
  const PatchSet patches = floors_under_boxes();
  const std::string path = temp_path("radwalk_contact_pair.obj");
  write_obj(path, patches);
  const std::string text = text_of(path);
  REQUIRE(text.find("\n# radwalk_contact_pair 1 3\n# radwalk_contact_pair 6 7\n") != std::string::npos);
  for (const bool strict : {false, true}) {
    INFO((strict ? "--strict" : "default"));
    Mesh back = read_obj(path);
    ValidationTolerances tol;
    tol.strict = strict;
    validate_mesh(back, tol);  // a refusal (--strict: any duplicate) would throw
    REQUIRE(back.face_count() == patches.size());
    for (std::size_t i = 0; i < patches.size(); ++i) {
      INFO("patch " << i);
      REQUIRE(back.source_face(i) == static_cast<long>(i));
      for (int k = 0; k < patches.corner_count(i); ++k)
        REQUIRE(back.vertices[static_cast<std::size_t>(back.faces[i][static_cast<std::size_t>(k)])] ==
                patches.corner(i, k));
      const Material& m = back.materials[static_cast<std::size_t>(back.face_material[i])];
      REQUIRE(m.name == patches.materials[static_cast<std::size_t>(patches.material[i])].name);
      REQUIRE_FALSE(m.two_sided);
    }
    REQUIRE(count_of(back, "back-to-back faces made two-sided") == 0);
    REQUIRE(count_of(back, "duplicate face") == 0);
  }

  // Another program's file (radwalk's first line replaced): the lines are comments, the pairs two-sided faces.
  const std::string other = temp_path("radwalk_contact_pair_other.obj");
  write_text(other, "# exported by another program" + text.substr(text.find('\n')));
  {
    Mesh back = read_obj(other);
    validate_mesh(back);
    CHECK(back.face_count() == patches.size() - 2);
    CHECK(count_of(back, "contact pair declaration ignored") == 0);
  }
  // Declarations that name no two faces of the file, or a face twice, are not used, with a warning each.
  for (const std::string bad : {"# radwalk_contact_pair 1 99", "# radwalk_contact_pair 1 1",
                                 "# radwalk_contact_pair 1", "# radwalk_contact_pair x 3",
                                 "# radwalk_contact_pair 1 3\n# radwalk_contact_pair 3 6"}) {
    INFO(bad);
    std::string edited = text;
    edited.replace(edited.find("# radwalk_contact_pair 1 3"), std::string("# radwalk_contact_pair 1 3").size(), bad);
    write_text(other, edited);
    Mesh back = read_obj(other);
    CHECK(count_of(back, "contact pair declaration ignored") >= 1);
    validate_mesh(back);
    CHECK(back.face_count() == patches.size() - 1 - (bad.find('\n') != std::string::npos ? 1 : 0));
  }
  std::filesystem::remove(path);
  std::filesystem::remove(other);
  std::filesystem::remove(std::filesystem::path(path).replace_extension(".mtl"));
}
