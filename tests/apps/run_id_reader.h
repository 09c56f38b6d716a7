#pragma once
// The run id (apps/run_metadata.h) of any output radwalk writes, read back the way a user's tool would: the JSON
// key, the .vtp field data, the CSV column, the comment of .mtx/.obj/.mtl/.py, the EXR header attribute, the PNG
// tEXt chunk. "" when the file has none.
#include <vtkAbstractArray.h>
#include <vtkFieldData.h>
#include <vtkStringArray.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "../io/vtp_test_helpers.h"
#include "io/exr_writer.h"
#include "io/png_writer.h"

inline std::string file_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A CSV's text without its last column, the run id (it differs between runs whose options or inputs differ).
inline std::string csv_without_run_id(const std::string& csv) {
  std::string out, line;
  std::istringstream in(csv);
  while (std::getline(in, line)) out += line.substr(0, line.rfind(',')) + "\n";
  return out;
}

inline std::string run_id_in(const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".json") return nlohmann::json::parse(file_text(path)).value("run_id", std::string());
  if (ext == ".vtp") {
    auto poly = read_vtp(path.string());
    auto* a = vtkStringArray::SafeDownCast(poly->GetFieldData()->GetAbstractArray("run_id"));
    return a && a->GetNumberOfValues() == 1 ? a->GetValue(0) : std::string();
  }
  if (ext == ".exr") return radwalk::read_exr_run_id(path.string());
  if (ext == ".png") return radwalk::png_text(file_text(path), "run_id");
  std::ifstream in(path);
  std::string line;
  if (ext == ".csv") {
    // The last column, the same on every row.
    std::getline(in, line);
    if (line.size() < 7 || line.compare(line.size() - 7, 7, ",run_id") != 0) return "";
    std::string id, row;
    while (std::getline(in, row)) {
      const std::string cell = row.substr(row.rfind(',') + 1);
      if (!id.empty() && cell != id) return "inconsistent";
      id = cell;
    }
    return id;
  }
  // .mtx ("% run_id X"), .obj, .mtl, .py ("# run_id X"): a comment line among the first few.
  for (int k = 0; k < 5 && std::getline(in, line); ++k)
    if (line.rfind("% run_id ", 0) == 0 || line.rfind("# run_id ", 0) == 0) return line.substr(9);
  return "";
}
