#include "io/vtp_writer.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkTypeInt64Array.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <stdexcept>

#include "core/atomic_write.h"
#include "core/check.h"
#include "core/error.h"
#include "core/srgb.h"
#include "patch/display_mesh.h"

namespace radwalk {
namespace {

void check_name(const std::string& name) {
  if (name.empty() || paraview_name(name) != name || is_calculator_reserved(name) ||
      std::isdigit(static_cast<unsigned char>(name[0])))
    throw std::logic_error("write_vtp: '" + name + "' is not a name ParaView's Calculator accepts");
}

void name_rgb(vtkDataArray* a) {
  a->SetComponentName(0, "R");
  a->SetComponentName(1, "G");
  a->SetComponentName(2, "B");
}

vtkNew<vtkDoubleArray> real_array(const CellField& f, const std::vector<double>& values, std::size_t tuples) {
  vtkNew<vtkDoubleArray> a;
  a->SetName(f.name.c_str());
  a->SetNumberOfComponents(f.components);
  // The array reads `values` in place (save = 1: VTK neither copies nor frees it; it outlives the writer).
  a->SetArray(const_cast<double*>(values.data()), static_cast<vtkIdType>(tuples * f.components), 1);
  if (f.kind == FieldKind::quantity && f.components == 3) name_rgb(a);
  return a;
}

vtkNew<vtkUnsignedCharArray> srgb_array(const std::vector<double>& B, std::size_t tuples) {
  vtkNew<vtkUnsignedCharArray> a;
  a->SetName("B_srgb");
  a->SetNumberOfComponents(3);
  a->SetNumberOfTuples(static_cast<vtkIdType>(tuples));
  for (std::size_t k = 0; k < tuples * 3; ++k) a->SetValue(static_cast<vtkIdType>(k), srgb8_from_radiosity(B[k]));
  name_rgb(a);
  return a;
}

void add_field_data(vtkPolyData* poly, const VtpMetadata& metadata) {
  for (const auto& [key, value] : metadata.entries) {
    check_name(key);
    if (const auto* text = std::get_if<std::string>(&value)) {
      vtkNew<vtkStringArray> a;
      a->SetName(key.c_str());
      a->InsertNextValue(*text);
      poly->GetFieldData()->AddArray(a);
    } else if (const auto* real = std::get_if<double>(&value)) {
      vtkNew<vtkDoubleArray> a;
      a->SetName(key.c_str());
      a->InsertNextValue(*real);
      poly->GetFieldData()->AddArray(a);
    } else {
      vtkNew<vtkTypeInt64Array> a;
      a->SetName(key.c_str());
      a->InsertNextValue(std::get<std::int64_t>(value));
      poly->GetFieldData()->AddArray(a);
    }
  }
}

}  // namespace

void write_vtp(const std::string& path, const PatchSet& patches, const std::vector<CellField>& fields,
               const VtpMetadata& metadata) {
  const std::size_t n = patches.size();
  const DisplayMesh mesh = make_display_mesh(patches);
  // Points, polygons and real fields are VTK arrays over the display mesh's and the fields' own memory (no copy,
  // no virtual call per value: at 10^7 patches the per-value calls took much of the writer's time and the copies
  // several GB). save = 1: VTK never frees them; they outlive the writer.
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "display points are packed xyz triples");
  static_assert(sizeof(std::int64_t) == sizeof(vtkTypeInt64), "64-bit polygon offsets and ids");
  vtkNew<vtkDoubleArray> coordinates;
  coordinates->SetNumberOfComponents(3);
  coordinates->SetArray(reinterpret_cast<double*>(const_cast<Vec3*>(mesh.points.data())),
                        static_cast<vtkIdType>(3 * mesh.points.size()), 1);
  vtkNew<vtkPoints> points;
  points->SetData(coordinates);
  vtkNew<vtkTypeInt64Array> offsets, connectivity;
  offsets->SetArray(reinterpret_cast<vtkTypeInt64*>(const_cast<std::int64_t*>(mesh.offsets.data())),
                    static_cast<vtkIdType>(n + 1), 1);
  connectivity->SetArray(reinterpret_cast<vtkTypeInt64*>(const_cast<std::int64_t*>(mesh.ids.data())),
                         static_cast<vtkIdType>(mesh.ids.size()), 1);
  vtkNew<vtkCellArray> polys;
  polys->SetData(offsets, connectivity);
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(points);
  poly->SetPolys(polys);

  std::vector<std::vector<double>> point_values;  // the point fields' values, alive until the file is written
  point_values.reserve(fields.size());
  for (const CellField& f : fields) {
    check_name(f.name);
    RADWALK_CHECK_EQ(f.values.size(), n * static_cast<std::size_t>(f.components));  // a value per patch, component
    if (f.kind == FieldKind::count) {
      vtkNew<vtkTypeInt64Array> a;
      a->SetName(f.name.c_str());
      a->SetNumberOfComponents(f.components);
      a->SetNumberOfTuples(static_cast<vtkIdType>(n));
      for (std::size_t k = 0; k < f.values.size(); ++k)
        a->SetValue(static_cast<vtkIdType>(k), static_cast<std::int64_t>(std::llround(f.values[k])));
      poly->GetCellData()->AddArray(a);
      continue;
    }
    poly->GetCellData()->AddArray(real_array(f, f.values, n));
    if (f.kind != FieldKind::quantity) continue;
    const std::vector<double>& at_points =
        point_values.emplace_back(point_average(mesh, patches, f.values, f.components));
    poly->GetPointData()->AddArray(real_array(f, at_points, mesh.points.size()));
    if (f.name == "B" && f.components == 3) {
      poly->GetCellData()->AddArray(srgb_array(f.values, n));
      poly->GetPointData()->AddArray(srgb_array(at_points, mesh.points.size()));
      poly->GetCellData()->SetActiveScalars("B");
    }
  }
  add_field_data(poly, metadata);

  // VTK writes into memory, never to the disk: on a (nearly) full disk VTK 9.1's file writer crashed or reported
  // success for an empty file. The bytes then go through the atomic writer, which checks every byte on disk.
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->WriteToOutputStringOn();
  writer->SetInputData(poly);
  writer->SetDataModeToBinary();
  writer->SetCompressorTypeToZLib();
  if (writer->Write() != 1) throw InputError(path + ": VTK could not encode the file");
  const std::string bytes = writer->GetOutputString();
  if (bytes.empty()) throw InputError(path + ": VTK produced no output");
  write_atomically(path, [&](std::ostream& out) { out.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); });
}

void write_pvd(const std::string& path, const std::vector<std::pair<double, std::string>>& steps) {
  write_atomically(path, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
    for (const auto& [t, file] : steps)
      out << "    <DataSet timestep=\"" << t << "\" part=\"0\" file=\"" << file << "\"/>\n";
    out << "  </Collection>\n</VTKFile>\n";
  });
}

}  // namespace radwalk
