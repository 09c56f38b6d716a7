#include "core/error.h"

#include <sstream>

#include "core/check.h"

namespace radwalk {

std::string locate(const std::string& file, long line, long face, const std::string& what) {
  std::ostringstream s;
  s << file;
  if (line > 0) s << ':' << line;
  s << ": ";
  if (face >= 0) s << "face " << face << ": ";
  s << what;
  return s.str();
}

namespace detail {

std::string source_path(const char* file) {
  const std::string path(file);
  for (const char* root : {"/src/", "/apps/", "/tests/", "/bench/"}) {
    const auto at = path.rfind(root);
    if (at != std::string::npos) return path.substr(at + 1);
  }
  return path;
}

void fail_check(const char* file, int line, const char* expression) {
  throw InternalError(source_path(file) + ':' + std::to_string(line) + ": check failed: " + expression);
}

}  // namespace detail

}  // namespace radwalk
