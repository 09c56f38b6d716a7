#pragma once
// Helpers of the .vtp tests: read a file back with VTK's own reader, weld coincident corner points.
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLPolyDataReader.h>

#include <filesystem>
#include <map>
#include <string>
#include <tuple>

#include "patch/patch_set.h"

inline vtkSmartPointer<vtkPolyData> read_vtp(const std::string& path) {
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkSmartPointer<vtkPolyData> poly = reader->GetOutput();
  return poly;
}

inline std::string temp_file(const std::string& name) {
  return (std::filesystem::temp_directory_path() / name).string();
}

// Makes patches that share a corner position share the point (PatchBuilder gives every patch its own points).
inline void weld_points(radwalk::PatchSet& p) {
  std::map<std::tuple<double, double, double>, std::int32_t> index;
  std::vector<radwalk::Vec3> points;
  std::vector<std::int32_t> map(p.points.size());
  for (std::size_t k = 0; k < p.points.size(); ++k) {
    const auto key = std::make_tuple(p.points[k].x(), p.points[k].y(), p.points[k].z());
    const auto [it, fresh] = index.try_emplace(key, std::int32_t(points.size()));
    if (fresh) points.push_back(p.points[k]);
    map[k] = it->second;
  }
  for (auto& c : p.corners)
    for (auto& v : c)
      if (v >= 0) v = map[v];
  p.points = points;
}
