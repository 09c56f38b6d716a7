// VTK's vtkSTLWriter as an independent writer of STL: what it writes (ascii and binary) radwalk's reader reads as
// the triangles VTK was given, corner for corner.
#include <catch2/catch.hpp>

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSTLWriter.h>

#include <filesystem>
#include <string>

#include "mesh/read_stl.h"
#include "support/scene_formats.h"

using namespace radwalk;
namespace fs = std::filesystem;

TEST_CASE("STL written by VTK's vtkSTLWriter (ascii and binary) reads back as the same triangles", "[mesh][formats]") {
  const test::TriScene scene = test::box_with_panel();
  vtkNew<vtkPoints> points;
  for (const auto& v : scene.vertices) points->InsertNextPoint(v[0], v[1], v[2]);
  vtkNew<vtkCellArray> triangles;
  for (const auto& t : scene.triangles) {
    const vtkIdType ids[3] = {t.v[0], t.v[1], t.v[2]};
    triangles->InsertNextCell(3, ids);
  }
  vtkNew<vtkPolyData> data;
  data->SetPoints(points);
  data->SetPolys(triangles);
  const fs::path dir = fs::temp_directory_path() / ("radwalk_stl_reference_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (const bool binary : {false, true}) {
    INFO((binary ? "binary" : "ascii"));
    const std::string path = (dir / (binary ? "vtk_binary.stl" : "vtk_ascii.stl")).string();
    vtkNew<vtkSTLWriter> writer;
    writer->SetInputData(data);
    writer->SetFileName(path.c_str());
    if (binary)
      writer->SetFileTypeToBinary();
    else
      writer->SetFileTypeToASCII();
    REQUIRE(writer->Write() == 1);
    const Mesh mesh = read_stl(path);
    REQUIRE(mesh.face_count() == scene.triangles.size());
    for (std::size_t f = 0; f < mesh.face_count(); ++f)
      for (int k = 0; k < 3; ++k) {
        const Vec3& got = mesh.vertices[static_cast<std::size_t>(mesh.faces[f][k])];
        const auto& want = scene.vertices[static_cast<std::size_t>(scene.triangles[f].v[static_cast<std::size_t>(k)])];
        // VTK writes ascii with its own precision and binary as float32; every coordinate here is a multiple of
        // 1/4, exact in both.
        REQUIRE(got == Vec3(want[0], want[1], want[2]));
      }
  }
  fs::remove_all(dir);
}
