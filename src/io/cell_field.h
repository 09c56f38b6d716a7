#pragma once
// CellField: one named per-patch quantity with 1 or 3 components, the unit of exchange between solvers and
// writers (VTK cell data, CSV columns). values holds N * components numbers, patch-major.
//
// Names: `name` is the VTK array name and must work as an identifier in ParaView's Calculator and in Python
// (letters, digits, underscores; not a reserved word of the Calculator such as `var`): see paraview_name().
// `csv_name`, when not empty, is the CSV column name (or prefix) instead, so CSV headers stay as they were.
#include <string>
#include <vector>

#include "core/types.h"
#include "patch/patch_set.h"

namespace radwalk {

enum class FieldKind {
  quantity,  // real; 3 components are R, G, B. Cell data, plus a point field for smooth display
  geometry,  // real, cell data only (area; normal with components X, Y, Z)
  count,     // ids and counts (patch, face, rays, ...): a 64-bit integer cell array, no point field
};

struct CellField {
  std::string name;  // VTK array name; CSV column name (1 component) or prefix of NAME_r, NAME_g, NAME_b
  int components = 1;
  std::vector<double> values;
  FieldKind kind = FieldKind::quantity;
  std::string csv_name;  // CSV name if it differs from `name` (empty: the same)

  const std::string& column_name() const { return csv_name.empty() ? name : csv_name; }
};

// The fields every patch output carries: patch and face (counts), area and normal (geometry), rho and E (3); in a
// scene with two-sided faces (PatchSet::side not empty) also side (count, after face: 0 front, 1 back); in a scene
// with contact pairs (patch/contact_pairs.h: two front patches lying on each other back to back, as --contact-cut
// makes under objects that have a bottom) also contact_pair (count, after side: the pair's id, the same for its
// two patches, -1 for a patch in no pair), with which radwalk's reader keeps the pair as two one-sided faces.
// (The centroid goes to CSV as cx, cy, cz; VTK has the geometry itself.)
std::vector<CellField> patch_fields(const PatchSet& patches);

CellField scalar_field(const std::string& name, const std::vector<double>& values,
                       FieldKind kind = FieldKind::quantity);
// An RGB field from an N x 3 array (B, B_se, B_var, ...).
CellField rgb_field(const std::string& name, const PatchRgb& values);

// f with the CSV name csv_name (its VTK name unchanged).
CellField with_csv_name(CellField f, const std::string& csv_name);

// `name` made usable in ParaView's Calculator and Python: every character other than a letter, digit or
// underscore becomes an underscore ("mean_gather-absorption" -> "mean_gather_absorption"). Reserved words are
// not renamed here: a field must not be one (the commands call the per-walk variance B_var, not var).
std::string paraview_name(const std::string& name);

// A word ParaView's Calculator (ExprTk) or Python reserves, compared without case where the Calculator ignores it:
// var, if, else, for, while, repeat, until, switch, case, default, break, continue, return, and, or, not, nand,
// nor, xor, xnor, in, like, ilike, true, false, null, swap, inf, pi, epsilon, iHat, jHat, kHat, and Python's
// keywords (lambda, def, ...).
bool is_calculator_reserved(const std::string& name);

}  // namespace radwalk
