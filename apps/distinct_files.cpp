#include "apps/distinct_files.h"

#include <filesystem>

#include <sys/stat.h>

#include "core/atomic_write.h"
#include "core/standard_output.h"

namespace radwalk::app {
namespace fs = std::filesystem;
namespace {

// The two names are the same file (see distinct_files.h).
bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  const fs::path pa = fs::weakly_canonical(fs::absolute(output_target(a), ec), ec);
  const fs::path pb = fs::weakly_canonical(fs::absolute(output_target(b), ec), ec);
  if (pa == pb) return true;
  struct stat sa {}, sb {};
  return ::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0 && sa.st_dev == sb.st_dev &&
         sa.st_ino == sb.st_ino;
}

}  // namespace

std::vector<NamedFile> output_files_of(const std::string& role, const std::string& path) {
  if (path.empty()) return {};
  std::vector<NamedFile> files = {{role, path}};
  const fs::path p(path);
  if (p.extension() == ".obj") files.push_back({role + " (its .mtl)", fs::path(p).replace_extension(".mtl").string()});
  if (p.extension() == ".exr")
    files.push_back({role + " (its standard-error image)", fs::path(p).replace_extension(".se.exr").string()});
  return files;
}

std::string check_distinct_files(const std::vector<NamedFile>& outputs, const std::vector<NamedFile>& inputs) {
  for (std::size_t k = 0; k < outputs.size(); ++k) {
    if (outputs[k].path.empty()) continue;
    if (is_standard_output(outputs[k].path)) {  // a stream, not a file: never an input; one output at most
      for (std::size_t l = 0; l < k; ++l)
        if (is_standard_output(outputs[l].path))
          return outputs[l].role + " - and " + outputs[k].role +
                 " -: only one output can go to standard output; give the other a file name";
      continue;
    }
    for (const NamedFile& in : inputs)
      if (!in.path.empty() && same_file(outputs[k].path, in.path))
        return outputs[k].path + ": " + outputs[k].role + " would overwrite " + in.role +
               "; radwalk never writes over an input (choose another output name)";
    for (std::size_t l = 0; l < k; ++l)
      if (!outputs[l].path.empty() && same_file(outputs[k].path, outputs[l].path))
        return outputs[k].path + ": " + outputs[k].role + " and " + outputs[l].role +
               " name the same file; give each output its own name";
  }
  return "";
}

}  // namespace radwalk::app
