#include "io/csv_writer.h"

#include <cmath>
#include <cstdio>
#include <ostream>

#include "core/standard_output.h"

namespace radwalk {

std::string csv_text(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

std::string csv_number(double v) {
  if (!std::isfinite(v)) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.12g", v);
  return buf;
}

void write_csv_table(const std::string& path, const std::vector<std::string>& header,
                     const std::vector<std::vector<std::string>>& rows, const std::string& run_id) {
  const std::string last = run_id.empty() ? "" : "," + run_id;
  write_output(path, [&](std::ostream& out) {
    for (std::size_t k = 0; k < header.size(); ++k) out << (k ? "," : "") << header[k];
    out << (run_id.empty() ? "" : ",run_id") << '\n';
    for (const auto& row : rows) {
      for (std::size_t k = 0; k < row.size(); ++k) out << (k ? "," : "") << row[k];
      out << last << '\n';
    }
  });
}

void write_patch_csv(const std::string& path, const PatchSet& patches, const std::vector<CellField>& extra,
                     const std::string& run_id) {
  static const char* kChannel[3] = {"_r", "_g", "_b"};
  std::vector<std::string> header = {"patch", "face",  "area",  "cx",  "cy",  "cz",  "nx", "ny",
                                     "nz",    "rho_r", "rho_g", "rho_b", "E_r", "E_g", "E_b",
                                     "object", "group", "material"};
  const bool sides = !patches.side.empty();  // a scene with two-sided faces: "side" after "face"
  if (sides) header.insert(header.begin() + 2, "side");
  for (const CellField& f : extra) {
    if (f.components == 1) {
      header.push_back(f.column_name());
    } else {
      for (int c = 0; c < f.components; ++c) {
        std::string column = f.column_name();
        if (f.components == 3) {
          column += kChannel[c];
        } else {
          column += '_';
          column += std::to_string(c);
        }
        header.push_back(column);
      }
    }
  }
  if (!run_id.empty()) header.push_back("run_id");
  const std::string last = run_id.empty() ? "" : "," + run_id;
  const std::size_t n = patches.size();
  write_output(path, [&](std::ostream& out) {
    for (std::size_t k = 0; k < header.size(); ++k) out << (k ? "," : "") << header[k];
    out << '\n';
    for (std::size_t i = 0; i < n; ++i) {
      out << i << ',' << patches.face[i];
      if (sides) out << ',' << (patches.is_back(i) ? 1 : 0);
      out << ',' << csv_number(patches.area[i]);
      for (int c = 0; c < 3; ++c) out << ',' << csv_number(patches.centroid[i][c]);
      for (int c = 0; c < 3; ++c) out << ',' << csv_number(patches.normal[i][c]);
      for (int c = 0; c < 3; ++c) out << ',' << csv_number(patches.rho[i][c]);
      for (int c = 0; c < 3; ++c) out << ',' << csv_number(patches.E[i][c]);
      out << ',' << csv_text(patches.object_of(i)) << ',' << csv_text(patches.group_of(i)) << ','
          << csv_text(patches.material_of(i));
      for (const CellField& f : extra)
        for (int c = 0; c < f.components; ++c) out << ',' << csv_number(f.values[i * f.components + c]);
      out << last << '\n';
    }
  });
}

}  // namespace radwalk
