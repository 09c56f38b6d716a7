#include "io/cell_field.h"

#include <algorithm>
#include <cctype>

#include "patch/contact_pairs.h"

namespace radwalk {

std::vector<CellField> patch_fields(const PatchSet& patches) {
  const std::size_t n = patches.size();
  CellField patch{"patch", 1, {}, FieldKind::count, {}}, face{"face", 1, {}, FieldKind::count, {}};
  CellField area{"area", 1, {}, FieldKind::geometry, {}}, normal{"normal", 3, {}, FieldKind::geometry, {}};
  CellField rho{"rho", 3, {}, FieldKind::quantity, {}}, E{"E", 3, {}, FieldKind::quantity, {}};
  for (std::size_t i = 0; i < n; ++i) {
    patch.values.push_back(static_cast<double>(i));
    face.values.push_back(patches.face[i]);
    area.values.push_back(patches.area[i]);
    for (int c = 0; c < 3; ++c) {
      normal.values.push_back(patches.normal[i][c]);
      rho.values.push_back(patches.rho[i][c]);
      E.values.push_back(patches.E[i][c]);
    }
  }
  std::vector<CellField> fields = {patch, face};
  if (!patches.side.empty()) {
    CellField side{"side", 1, {}, FieldKind::count, {}};  // two-sided faces: 0 front, 1 back
    for (std::size_t i = 0; i < n; ++i) side.values.push_back(patches.is_back(i) ? 1 : 0);
    fields.push_back(std::move(side));
  }
  const std::vector<std::int32_t> pair = contact_pair_ids(patches);
  if (std::any_of(pair.begin(), pair.end(), [](std::int32_t k) { return k >= 0; }))
    fields.push_back(CellField{"contact_pair", 1, std::vector<double>(pair.begin(), pair.end()), FieldKind::count, {}});
  for (CellField* f : {&area, &normal, &rho, &E}) fields.push_back(std::move(*f));
  return fields;
}

CellField scalar_field(const std::string& name, const std::vector<double>& values, FieldKind kind) {
  return CellField{name, 1, values, kind, {}};
}

CellField rgb_field(const std::string& name, const PatchRgb& values) {
  CellField f{name, 3, {}, FieldKind::quantity, {}};
  f.values.reserve(static_cast<std::size_t>(values.rows()) * 3);
  for (Eigen::Index i = 0; i < values.rows(); ++i)
    for (int c = 0; c < 3; ++c) f.values.push_back(values(i, c));
  return f;
}

CellField with_csv_name(CellField f, const std::string& csv_name) {
  f.csv_name = csv_name;
  return f;
}

bool is_calculator_reserved(const std::string& name) {
  static const char* const kCalculator[] = {
      "var",   "if",  "else", "for",  "while", "repeat", "until", "switch", "case",  "default", "break", "continue",
      "return", "and", "or",  "not",  "nand",  "nor",    "xor",   "xnor",   "in",    "like",    "ilike", "true",
      "false", "null", "swap", "inf", "pi",    "epsilon", "ihat", "jhat",   "khat"};
  static const char* const kPython[] = {"None",   "True",  "False",  "as",   "assert", "async",  "await", "class",
                                        "def",    "del",   "elif",   "except", "finally", "from", "global", "import",
                                        "is",     "lambda", "nonlocal", "pass", "raise",  "try",   "with",  "yield"};
  std::string lower = name;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const char* w : kCalculator)
    if (lower == w) return true;
  for (const char* w : kPython)
    if (name == w) return true;
  return false;
}

std::string paraview_name(const std::string& name) {
  std::string out = name;
  for (char& ch : out)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '_') ch = '_';
  return out;
}

}  // namespace radwalk
