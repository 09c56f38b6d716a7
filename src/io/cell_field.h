#pragma once
// CellField: one named per-patch quantity with 1 or 3 components, the unit of exchange between solvers and
// writers (VTK cell data, CSV columns). values holds N * components numbers, patch-major.
#include <string>
#include <vector>

#include "core/types.h"
#include "patch/patch_set.h"

namespace radwalk {

struct CellField {
  std::string name;  // VTK array name; CSV column name (1 component) or prefix of NAME_r, NAME_g, NAME_b
  int components = 1;
  std::vector<double> values;
};

// The fields every patch output carries: patch, face, area, normal (3), rho (3), E (3).
// (The centroid goes to CSV as cx, cy, cz; VTK has the geometry itself.)
std::vector<CellField> patch_fields(const PatchSet& patches);

CellField scalar_field(const std::string& name, const std::vector<double>& values);
// An RGB field from an N x 3 array (B, B_se, var, ...).
CellField rgb_field(const std::string& name, const PatchRgb& values);

}  // namespace radwalk
