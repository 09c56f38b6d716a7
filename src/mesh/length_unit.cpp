#include "mesh/length_unit.h"

#include <cmath>
#include <utility>

#include "core/format_number.h"

namespace radwalk {

namespace {

const std::pair<const char*, double> kUnits[] = {
    {"mm", 1e-3}, {"cm", 1e-2}, {"m", 1.0}, {"in", 0.0254}, {"ft", 0.3048}};

}  // namespace

double metres_per(const std::string& unit) {
  for (const auto& [name, metres] : kUnits)
    if (unit == name) return metres;
  return 0;
}

const char* unit_names() { return "mm, cm, m, in, ft"; }

std::string LengthUnit::length() const {
  const std::string base = file_unit.empty() ? "mesh unit" : file_unit;
  if (scale == 1) return base;
  if (!file_unit.empty()) {
    // One new unit is (1 / scale) file units = metres_per(file_unit) / scale metres.
    const double metres = metres_per(file_unit) / scale;
    for (const auto& [name, m] : kUnits)
      if (std::abs(metres - m) <= 1e-9 * m) return name;
  }
  return format_number(1 / scale) + " " + base;
}

std::string LengthUnit::radiosity() const {
  const std::string unit = length();
  if (unit == "mesh unit") return "W per mesh unit^2";
  if (unit.find(' ') != std::string::npos) return "W/(" + unit + ")^2";
  return "W/" + unit + "^2";
}

void scale_mesh(Mesh& mesh, double scale) {
  if (scale == 1) return;
  for (Vec3& v : mesh.vertices) v *= scale;
}

}  // namespace radwalk
