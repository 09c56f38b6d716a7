// A .vtp radwalk wrote (io/vtp_writer.h) read back by radwalk's own .vtp reader (mesh/read_vtk.h): the same faces
// (the display mesh's T-junction points dropped again), reflectances, emissions and material names.
#include <catch2/catch.hpp>

#include <filesystem>

#include "io/cell_field.h"
#include "io/vtp_writer.h"
#include "mesh/read_vtk.h"
#include "patch/patch_builder.h"
#include "vtp_test_helpers.h"

using namespace radwalk;

TEST_CASE("vtk .vtp reader: a .vtp radwalk wrote reads back as the same mesh", "[io][vtp]") {
  // A wide floor under two tiles: the tiles' shared corner (1, 1, 0) lies on the floor's top edge, so the display
  // mesh inserts it into the floor's polygon (a T-junction point), which the reader drops.
  PatchBuilder b;
  const int floor = b.add_material("floor", Rgb(0.73, 0.5, 0.25));
  const int lamp = b.add_material("lamp", Rgb(0.1, 0.2, 0.3), Rgb(1, 2, 3));
  b.add_quad({0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}, floor);
  b.add_quad({0, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}, floor);
  b.add_quad({1, 1, 0}, {2, 1, 0}, {2, 2, 0}, {1, 2, 0}, lamp);
  b.add_triangle({0, 0, 1}, {0, 1, 1}, {1, 0, 1}, lamp);
  const PatchSet patches = b.build();
  const auto path = temp_file("radwalk_read_back.vtp");
  write_vtp(path, patches, patch_fields(patches));
  const Mesh back = read_vtk_polydata(path);
  std::filesystem::remove(path);
  REQUIRE(back.face_count() == patches.size());
  for (std::size_t i = 0; i < patches.size(); ++i) {
    INFO("patch " << i);
    REQUIRE(back.corner_count(i) == patches.corner_count(i));
    for (int k = 0; k < patches.corner_count(i); ++k)
      REQUIRE(back.vertices[static_cast<std::size_t>(back.faces[i][static_cast<std::size_t>(k)])] ==
              patches.corner(i, k));
    const Material& m = back.materials[static_cast<std::size_t>(back.face_material[i])];
    const Material& original = patches.materials[static_cast<std::size_t>(patches.material[i])];
    REQUIRE(m.name == original.name);
    REQUIRE((m.Kd == original.Kd).all());
    // E = pi Ke is written, Ke = E / pi read: two roundings, each within half an ulp.
    for (int c = 0; c < 3; ++c) REQUIRE(m.Ke[c] == Approx(original.Ke[c]).epsilon(4e-16).margin(0));
    REQUIRE_FALSE(m.reflectance_missing);
  }
  REQUIRE(back.materials.size() == 2);
  REQUIRE(back.findings.empty());
}
