#include "apps/output_files.h"

#include <filesystem>
#include <vector>

#include "core/atomic_write.h"
#include "core/error.h"
#include "core/path_length.h"
#include "core/standard_output.h"

namespace radwalk::app {
namespace {

struct Format {
  OutputFile kind;
  const char* written;                  // what the file holds, in words
  std::vector<std::string> extensions;  // accepted file name endings
};

const Format kFormats[] = {
    {OutputFile::vtp, "VTK XML PolyData", {".vtp"}},
    {OutputFile::vtp_or_obj, "VTK XML PolyData or OBJ (+ .mtl)", {".vtp", ".obj"}},
    {OutputFile::csv, "CSV", {".csv"}},
    {OutputFile::json, "a JSON summary", {".json"}},
    {OutputFile::matrix_market, "a Matrix Market (.mtx) or binary CSR (.npz) matrix", {".mtx", ".npz"}},
    {OutputFile::image, "a PNG (sRGB) or OpenEXR (linear) image", {".png", ".exr"}},
};

const Format& format_of(OutputFile kind) {
  for (const Format& f : kFormats)
    if (f.kind == kind) return f;
  return kFormats[0];
}

}  // namespace

std::string check_output_file(const std::string& path, OutputFile kind) {
  if (path.empty()) return "";
  // "-": standard output (core/standard_output.h), for the text outputs a pipeline reads.
  if (is_standard_output(path) && (kind == OutputFile::csv || kind == OutputFile::json)) return "";
  if (const std::string too_long = path_length_problem(path); !too_long.empty()) return too_long;
  const Format& format = format_of(kind);
  const std::string ext = std::filesystem::path(path).extension().string();
  bool known = false;
  std::string endings;
  for (std::size_t k = 0; k < format.extensions.size(); ++k) {
    known = known || ext == format.extensions[k];
    endings += (k == 0 ? "" : " or ") + format.extensions[k];
  }
  if (!known)
    return path + ": the file written is " + format.written + ", so its name must end in " + endings;
  try {
    require_output_directory(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string output_extensions(OutputFile kind) {
  std::string text;
  for (const std::string& e : format_of(kind).extensions) text += (text.empty() ? "" : "|") + e;
  return text;
}

std::string check_series_directory(const std::string& dir) {
  if (dir.empty())
    return "needs a directory name (an empty one would put the series into the current directory)";
  return path_length_problem(dir);
}

}  // namespace radwalk::app
