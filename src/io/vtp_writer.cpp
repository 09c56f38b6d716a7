#include "io/vtp_writer.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataWriter.h>

#include <ostream>

#include "core/atomic_write.h"
#include "core/check.h"
#include "core/error.h"

namespace radwalk {
namespace {

vtkNew<vtkDoubleArray> make_array(const std::string& name, int components, std::size_t tuples) {
  vtkNew<vtkDoubleArray> a;
  a->SetName(name.c_str());
  a->SetNumberOfComponents(components);
  a->SetNumberOfTuples(static_cast<vtkIdType>(tuples));
  return a;
}

}  // namespace

void write_vtp(const std::string& path, const PatchSet& patches, const std::vector<CellField>& fields) {
  const std::size_t n = patches.size();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(patches.points.size()));
  for (std::size_t p = 0; p < patches.points.size(); ++p)
    points->SetPoint(static_cast<vtkIdType>(p), patches.points[p].data());

  vtkNew<vtkCellArray> polys;
  for (std::size_t i = 0; i < n; ++i) {
    vtkIdType ids[4];
    const int k = patches.corner_count(i);
    for (int c = 0; c < k; ++c) ids[c] = patches.corners[i][c];
    polys->InsertNextCell(k, ids);
  }
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(points);
  poly->SetPolys(polys);

  // Area weights of each point: the sum of the areas of the patches that use it.
  std::vector<double> point_weight(patches.points.size(), 0.0);
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < patches.corner_count(i); ++c) point_weight[patches.corners[i][c]] += patches.area[i];

  for (const CellField& f : fields) {
    RADWALK_CHECK_EQ(f.values.size(), n * static_cast<std::size_t>(f.components));  // a value per patch, component
    auto cell = make_array(f.name, f.components, n);
    auto point = make_array(f.name, f.components, patches.points.size());
    point->Fill(0.0);
    for (std::size_t i = 0; i < n; ++i) {
      for (int c = 0; c < f.components; ++c) {
        const double v = f.values[i * f.components + c];
        cell->SetComponent(static_cast<vtkIdType>(i), c, v);
        for (int k = 0; k < patches.corner_count(i); ++k) {
          const auto p = static_cast<vtkIdType>(patches.corners[i][k]);
          point->SetComponent(p, c, point->GetComponent(p, c) + patches.area[i] * v);
        }
      }
    }
    for (std::size_t p = 0; p < patches.points.size(); ++p)
      if (point_weight[p] > 0)
        for (int c = 0; c < f.components; ++c)
          point->SetComponent(static_cast<vtkIdType>(p), c,
                              point->GetComponent(static_cast<vtkIdType>(p), c) / point_weight[p]);
    poly->GetCellData()->AddArray(cell);
    poly->GetPointData()->AddArray(point);
  }

  write_atomically_via_path(path, [&](const std::string& tmp) {
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetFileName(tmp.c_str());
    writer->SetInputData(poly);
    writer->SetDataModeToBinary();
    writer->SetCompressorTypeToZLib();
    if (writer->Write() != 1) throw InputError(path + ": VTK could not write the file");
  });
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
