// A .vtp radwalk wrote (io/vtp_writer.h) read back by radwalk's own .vtp reader (mesh/read_vtk.h): the same faces
// (the display mesh's T-junction points dropped again), reflectances, emissions and material names; and the same
// .vtp converted to legacy .vtk by VTK's writer, read back by radwalk's own legacy reader; contact pairs (a floor
// piece and the bottom lying on it) read back as two one-sided faces from radwalk's file only.
#include <catch2/catch.hpp>

#include <filesystem>
#include <functional>
#include <utility>
#include <vector>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPolyDataWriter.h>
#include <vtkXMLPolyDataWriter.h>

#include "io/cell_field.h"
#include "io/vtp_writer.h"
#include "mesh/read_vtk.h"
#include "mesh/validate.h"
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

TEST_CASE("vtk .vtk reader: a radwalk .vtp that VTK's legacy writer converts reads back as the .vtp does", "[io][vtk]") {
  // radwalk writes no legacy .vtk; a user gets one by converting radwalk's .vtp (ParaView's "Save Data" as .vtk is
  // vtkPolyDataWriter): the .vtp read by VTK's XML reader, written by vtkPolyDataWriter in every encoding and cell
  // layout, then read by radwalk's legacy reader, is the mesh radwalk's .vtp reader reads. BINARY keeps every double,
  // so it is the same bit for bit; ASCII writes 11 significant digits, so the values agree to 1e-10 relative.
  PatchBuilder b;
  const int floor = b.add_material("floor tiles", Rgb(0.73, 0.5, 0.25));
  const int lamp = b.add_material("lamp", Rgb(0.1, 0.2, 0.3), Rgb(1, 2, 3));
  b.add_quad({0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}, floor);
  b.add_quad({0, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}, floor);
  b.add_quad({1, 1, 0}, {2, 1, 0}, {2, 2, 0}, {1, 2, 0}, lamp);
  b.add_triangle({0, 0, 1}, {0, 1, 1}, {1, 0, 1}, lamp);
  const PatchSet patches = b.build();
  const auto path = temp_file("radwalk_legacy_round_trip.vtp");
  write_vtp(path, patches, patch_fields(patches));
  const Mesh from_vtp = read_vtk_polydata(path);
  const vtkSmartPointer<vtkPolyData> poly = read_vtp(path);
  std::filesystem::remove(path);
  for (const int version : {42, 51})
    for (const bool binary : {false, true}) {
      INFO("version " << version << (binary ? " BINARY" : " ASCII"));
      vtkNew<vtkPolyDataWriter> writer;
      writer->SetInputData(poly);
      writer->WriteToOutputStringOn();
      writer->SetFileVersion(version);
      if (binary) writer->SetFileTypeToBinary();
      REQUIRE(writer->Write() == 1);
      const Mesh m = read_vtk_polydata_bytes("converted.vtk", writer->GetOutputStdString(), false);
      REQUIRE(m.vertices == from_vtp.vertices);
      REQUIRE(m.faces == from_vtp.faces);
      REQUIRE(m.face_material == from_vtp.face_material);
      REQUIRE(m.materials.size() == from_vtp.materials.size());
      for (std::size_t k = 0; k < m.materials.size(); ++k) {
        REQUIRE(m.materials[k].name == from_vtp.materials[k].name);
        for (int c = 0; c < 3; ++c) {
          if (binary) {
            REQUIRE(m.materials[k].Kd[c] == from_vtp.materials[k].Kd[c]);
            REQUIRE(m.materials[k].Ke[c] == from_vtp.materials[k].Ke[c]);
          } else {
            REQUIRE(m.materials[k].Kd[c] == Approx(from_vtp.materials[k].Kd[c]).epsilon(1e-10).margin(0));
            REQUIRE(m.materials[k].Ke[c] == Approx(from_vtp.materials[k].Ke[c]).epsilon(1e-10).margin(0));
          }
        }
      }
      REQUIRE(m.findings.empty());
    }
}

namespace {

// A floor of two quads facing up, a box's bottom lying on the first back to back (its corners starting elsewhere,
// as a cut floor piece and the bottom over it come out of patching) and the box's side rising from it: patches 0
// and 2 are a contact pair (patch/contact_pairs.h).
PatchSet floor_under_a_box() {
  PatchBuilder b;
  const int floor = b.add_material("floor", Rgb(0.7, 0.6, 0.5));
  const int box = b.add_material("box", Rgb(0.2, 0.3, 0.4));
  const int lamp = b.add_material("lamp", Rgb::Zero(), Rgb::Constant(1));
  b.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, floor);
  b.add_quad({1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, floor);
  b.add_quad({1, 1, 0}, {1, 0, 0}, {0, 0, 0}, {0, 1, 0}, box);
  b.add_quad({0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}, box);
  b.add_quad({0, 0, 3}, {0, 1, 3}, {1, 1, 3}, {1, 0, 3}, lamp);
  return b.build();
}

std::size_t count_of(const Mesh& m, const std::string& kind) {
  std::size_t n = 0;
  for (const Finding& f : m.findings) n += f.kind == kind;
  return n;
}

}  // namespace

TEST_CASE("vtk .vtp reader: a contact pair radwalk wrote reads back as its two one-sided faces", "[io][vtp][contact]") {
  const PatchSet patches = floor_under_a_box();
  const auto path = temp_file("radwalk_contact_pair.vtp");
  write_vtp(path, patches, patch_fields(patches));
  const vtkSmartPointer<vtkPolyData> poly = read_vtp(path);
  vtkDataArray* pair = poly->GetCellData()->GetArray("contact_pair");
  REQUIRE(pair != nullptr);
  REQUIRE(pair->GetNumberOfTuples() == 5);
  for (const auto& [cell, id] : std::vector<std::pair<int, double>>{{0, 0}, {1, -1}, {2, 0}, {3, -1}, {4, -1}})
    REQUIRE(pair->GetTuple1(cell) == id);
  for (const bool strict : {false, true}) {
    INFO((strict ? "--strict" : "default"));
    Mesh back = read_vtk_polydata(path);
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
  std::filesystem::remove(path);
}

TEST_CASE("vtk .vtp reader: back-to-back duplicates of another program's file, or of an edited one, are still "
          "made one two-sided face", "[io][vtp][contact]") {
  // The same file as VTK's writer writes it after an edit: (a) as it is (radwalk's pair honoured), (b) its cells
  // renumbered (the `patch` field no longer numbers them in order: the pair ids may name other cells now), (c)
  // without `patch` (another program's file), (d) without `contact_pair` (a file that declares no pair), (e) the
  // pair's id held by one cell only. Only (a) keeps the two faces; the others repair as any scene file.
  const PatchSet patches = floor_under_a_box();
  const auto path = temp_file("radwalk_contact_pair_edited.vtp");
  write_vtp(path, patches, patch_fields(patches));
  const vtkSmartPointer<vtkPolyData> written = read_vtp(path);
  std::filesystem::remove(path);
  const auto edited = [&](const std::function<void(vtkPolyData*)>& edit) {
    vtkNew<vtkPolyData> copy;
    copy->DeepCopy(written);
    edit(copy);
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetInputData(copy);
    writer->SetDataModeToAscii();
    writer->WriteToOutputStringOn();
    REQUIRE(writer->Write() == 1);
    Mesh m = read_vtk_polydata_bytes("edited.vtp", writer->GetOutputString(), true);
    validate_mesh(m);
    return m;
  };
  const Mesh as_is = edited([](vtkPolyData*) {});
  REQUIRE(as_is.face_count() == 5);
  REQUIRE(count_of(as_is, "back-to-back faces made two-sided") == 0);
  const std::vector<std::function<void(vtkPolyData*)>> edits = {
      [](vtkPolyData* p) { p->GetCellData()->GetArray("patch")->SetTuple1(4, 7); },
      [](vtkPolyData* p) { p->GetCellData()->RemoveArray("patch"); },
      [](vtkPolyData* p) { p->GetCellData()->RemoveArray("contact_pair"); },
      [](vtkPolyData* p) { p->GetCellData()->GetArray("contact_pair")->SetTuple1(2, 5); }};
  for (std::size_t e = 0; e < edits.size(); ++e) {
    INFO("edit " << e);
    const Mesh m = edited(edits[e]);
    REQUIRE(m.face_count() == 4);  // the pair is one two-sided face
    REQUIRE(count_of(m, "back-to-back faces made two-sided") == 1);
    REQUIRE(m.materials[static_cast<std::size_t>(m.face_material[0])].two_sided);
  }
}

TEST_CASE("vtk .vtp reader: back cells tiled otherwise than their fronts are read as the fronts' backs and said",
          "[io][vtp]") {
  // A two-sided face (one quad) whose back is one reversed quad, or two halves (as a hierarchical run, which refines
  // the two sides apart, writes it): both read back as the one two-sided face; only the halves are said, once,
  // naming how many back cells are not used.
  for (const bool halves : {false, true}) {
    INFO((halves ? "back in two halves" : "back as the front's reversed copy"));
    PatchBuilder b;
    const int board = b.add_material("board", Rgb(0.5, 0.5, 0.5));
    const int lamp = b.add_material("lamp", Rgb::Zero(), Rgb::Constant(1));
    b.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, board);
    if (halves) {
      b.add_quad({0, 0, 0}, {0, 1, 0}, {0.5, 1, 0}, {0.5, 0, 0}, board);
      b.add_quad({0.5, 0, 0}, {0.5, 1, 0}, {1, 1, 0}, {1, 0, 0}, board);
    } else {
      b.add_quad({0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}, board);
    }
    b.add_quad({0, 0, 2}, {0, 1, 2}, {1, 1, 2}, {1, 0, 2}, lamp);
    PatchSet patches = b.build();
    const std::size_t n = patches.size();
    patches.face.assign(n, 0);
    patches.face[n - 1] = 1;
    patches.side.assign(n, Side::back);
    patches.side[0] = Side::front;
    patches.side[n - 1] = Side::one_sided;
    patches.materials[static_cast<std::size_t>(board)].two_sided = true;
    const auto path = temp_file("radwalk_back_tiling.vtp");
    write_vtp(path, patches, patch_fields(patches));
    const Mesh back = read_vtk_polydata(path);
    std::filesystem::remove(path);
    REQUIRE(back.face_count() == 2);  // the board (its back cells stand for nothing of their own) and the lamp
    REQUIRE(back.materials[static_cast<std::size_t>(back.face_material[0])].two_sided);
    REQUIRE(count_of(back, "back cells tiled otherwise") == (halves ? 1u : 0u));
    for (const Finding& f : back.findings)
      if (f.kind == "back cells tiled otherwise") REQUIRE_THAT(f.message, Catch::Contains("2 back cells"));
  }
}
