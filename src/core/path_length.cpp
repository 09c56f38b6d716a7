#include "core/path_length.h"

#include <climits>

#include "core/error.h"

namespace radwalk {
namespace {

// The path as named in a message: whole when short, else its first and last 40 bytes around "...".
std::string abbreviated(const std::string& path) {
  constexpr std::size_t kShown = 40;
  if (path.size() <= 2 * kShown + 3) return path;
  return path.substr(0, kShown) + "..." + path.substr(path.size() - kShown);
}

}  // namespace

std::string path_length_problem(const std::string& path) {
  constexpr std::size_t kMaxPath = PATH_MAX - 1, kMaxName = NAME_MAX;
  if (path.size() > kMaxPath)
    return abbreviated(path) + ": path too long (" + std::to_string(path.size()) + " bytes; at most " +
           std::to_string(kMaxPath) + ")";
  std::size_t start = 0;
  while (start <= path.size()) {
    std::size_t end = path.find('/', start);
    if (end == std::string::npos) end = path.size();
    if (end - start > kMaxName)
      return abbreviated(path) + ": path too long (a component of " + std::to_string(end - start) +
             " bytes; at most " + std::to_string(kMaxName) + " between slashes)";
    start = end + 1;
  }
  return "";
}

void require_path_length(const std::string& path) {
  const std::string problem = path_length_problem(path);
  if (!problem.empty()) throw InputError(problem);
}

}  // namespace radwalk
