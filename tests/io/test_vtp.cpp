// The .vtp reads back through VTK's own reader with the same arrays and values.
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>

#include <catch2/catch.hpp>
#include <filesystem>

#include "io/vtp_writer.h"
#include "patch/patch_builder.h"

using namespace radwalk;

static PatchSet two_patches() {
  PatchBuilder b;
  const int white = b.add_material("white", Rgb(0.73, 0.5, 0.25));
  const int light = b.add_material("light", Rgb(0.1, 0.2, 0.3), Rgb(1, 2, 3));
  b.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, white);
  b.add_triangle({0, 0, 1}, {0, 1, 1}, {1, 0, 1}, light);
  return b.build();
}

TEST_CASE("write_vtp: cell arrays read back with VTK's reader", "[io][vtp]") {
  const PatchSet patches = two_patches();
  auto fields = patch_fields(patches);
  PatchRgb B(2, 3);
  B << 1.5, 2.5, 3.5, 4.5, 5.5, 6.5;
  fields.push_back(rgb_field("B", B));

  const auto path = (std::filesystem::temp_directory_path() / "radwalk_test.vtp").string();
  write_vtp(path, patches, fields);

  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkPolyData* poly = reader->GetOutput();
  REQUIRE(poly->GetNumberOfCells() == 2);
  REQUIRE(poly->GetNumberOfPoints() == 7);
  for (const char* name : {"patch", "face", "area", "normal", "rho", "E", "B"}) {
    INFO(name);
    REQUIRE(poly->GetCellData()->GetArray(name) != nullptr);
    REQUIRE(poly->GetPointData()->GetArray(name) != nullptr);
  }
  vtkDataArray* area = poly->GetCellData()->GetArray("area");
  CHECK(area->GetComponent(0, 0) == Approx(1.0));
  CHECK(area->GetComponent(1, 0) == Approx(0.5));
  vtkDataArray* rho = poly->GetCellData()->GetArray("rho");
  CHECK(rho->GetComponent(0, 0) == 0.73);  // exact: doubles are stored as doubles
  vtkDataArray* E = poly->GetCellData()->GetArray("E");
  CHECK(E->GetComponent(1, 2) == Approx(3 * kPi));
  vtkDataArray* b = poly->GetCellData()->GetArray("B");
  CHECK(b->GetNumberOfComponents() == 3);
  CHECK(b->GetComponent(1, 1) == 5.5);
  vtkDataArray* normal = poly->GetCellData()->GetArray("normal");
  CHECK(normal->GetComponent(0, 2) == Approx(1.0));
  CHECK(normal->GetComponent(1, 2) == Approx(-1.0));
  // Point data: no point is shared here, so each point carries its patch's value.
  CHECK(poly->GetPointData()->GetArray("B")->GetComponent(0, 0) == Approx(1.5));
  std::filesystem::remove(path);
}

TEST_CASE("write_vtp: a shared point carries the area-weighted average", "[io][vtp]") {
  PatchSet p = two_patches();
  // Make the triangle share point 0 of the quad.
  p.corners[1][0] = 0;
  auto fields = std::vector<CellField>{scalar_field("x", {1.0, 4.0})};
  const auto path = (std::filesystem::temp_directory_path() / "radwalk_test_shared.vtp").string();
  write_vtp(path, p, fields);
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  const double a0 = p.area[0], a1 = p.area[1];
  CHECK(reader->GetOutput()->GetPointData()->GetArray("x")->GetComponent(0, 0) ==
        Approx((a0 * 1.0 + a1 * 4.0) / (a0 + a1)));
  std::filesystem::remove(path);
}
