#include "support/artifacts.h"

#include <catch2/catch.hpp>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "io/cell_field.h"
#include "io/vtp_writer.h"

namespace radwalk::test {

namespace {

std::string file_name_part(const std::string& text) {
  std::string s = text;
  for (char& c : s) {
    const bool keep = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' ||
                      c == '-' || c == '_';
    if (!keep) c = '_';
  }
  return s;
}

}  // namespace

std::filesystem::path artifact_dir() {
  if (const char* dir = std::getenv("RADWALK_TEST_ARTIFACTS"); dir && *dir) return dir;
  return RADWALK_TEST_ARTIFACTS_DIR;
}

std::filesystem::path artifact_path(const std::string& what, const std::string& extension) {
  const std::filesystem::path dir = artifact_dir();
  std::filesystem::create_directories(dir);
  const std::string test = Catch::getResultCapture().getCurrentTestName();
  const std::filesystem::path path = dir / (file_name_part(test) + "--" + file_name_part(what) + "." + extension);
  // Also on stderr in one line (Catch2's console reporter wraps long messages).
  std::fprintf(stderr, "radwalk test artifact: %s\n", path.string().c_str());
  return path;
}

std::string artifact_number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

std::string write_artifact_csv(const std::string& what, const std::vector<std::string>& header,
                               const std::vector<std::vector<std::string>>& rows) {
  const std::filesystem::path path = artifact_path(what, "csv");
  std::ofstream out(path);
  const auto line = [&](const std::vector<std::string>& cells) {
    for (std::size_t k = 0; k < cells.size(); ++k) out << (k ? "," : "") << cells[k];
    out << '\n';
  };
  line(header);
  for (const auto& row : rows) line(row);
  return path.string();
}

std::string write_artifact_patch_z(const std::string& what, const PatchSet& patches, const PatchRgb& estimate,
                                   const PatchRgb& se, const PatchRgb& expected, const PatchRgb& z) {
  const std::filesystem::path path = artifact_path(what, "vtp");
  std::vector<CellField> fields = patch_fields(patches);
  fields.push_back(rgb_field("estimate", estimate));
  fields.push_back(rgb_field("se", se));
  fields.push_back(rgb_field("expected", expected));
  fields.push_back(rgb_field("z", z));
  write_vtp(path.string(), patches, fields);
  return path.string();
}

}  // namespace radwalk::test
