#include "io/csv_writer.h"

#include <charconv>
#include <cmath>
#include <ostream>

#include "core/standard_output.h"

namespace radwalk {

void append_csv_text(std::string& out, const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) {
    out += text;
    return;
  }
  out += '"';
  for (const char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
}

std::string csv_text(const std::string& text) {
  std::string s;
  append_csv_text(s, text);
  return s;
}

// printf's %.12g, by std::to_chars (the same characters: C++17 [utility.to.chars] defines the precision form as
// printf's), without printf's format parsing and locale.
void append_csv_number(std::string& out, double v) {
  if (!std::isfinite(v)) return;
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 12);
  out.append(buf, r.ptr);
}

std::string csv_number(double v) {
  std::string s;
  append_csv_number(s, v);
  return s;
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
  // Rows are formatted into one buffer, written out every kFlushBytes (no stream insertion per cell).
  constexpr std::size_t kFlushBytes = std::size_t(1) << 16;
  write_output(path, [&](std::ostream& out) {
    std::string buf;
    buf.reserve(kFlushBytes + 4096);
    for (std::size_t k = 0; k < header.size(); ++k) {
      if (k) buf += ',';
      buf += header[k];
    }
    buf += '\n';
    const auto integer = [&buf](auto v) {
      char d[24];
      buf.append(d, std::to_chars(d, d + sizeof d, v).ptr);
    };
    const auto number = [&buf](double v) {
      buf += ',';
      append_csv_number(buf, v);
    };
    for (std::size_t i = 0; i < n; ++i) {
      integer(i);
      buf += ',';
      integer(patches.face[i]);
      if (sides) buf += patches.is_back(i) ? ",1" : ",0";
      number(patches.area[i]);
      for (int c = 0; c < 3; ++c) number(patches.centroid[i][c]);
      for (int c = 0; c < 3; ++c) number(patches.normal[i][c]);
      for (int c = 0; c < 3; ++c) number(patches.rho[i][c]);
      for (int c = 0; c < 3; ++c) number(patches.E[i][c]);
      buf += ',';
      append_csv_text(buf, patches.object_of(i));
      buf += ',';
      append_csv_text(buf, patches.group_of(i));
      buf += ',';
      append_csv_text(buf, patches.material_of(i));
      for (const CellField& f : extra)
        for (int c = 0; c < f.components; ++c) number(f.values[i * f.components + c]);
      buf += last;
      buf += '\n';
      if (buf.size() >= kFlushBytes) {
        out.write(buf.data(), std::streamsize(buf.size()));
        buf.clear();
      }
    }
    out.write(buf.data(), std::streamsize(buf.size()));
  });
}

}  // namespace radwalk
