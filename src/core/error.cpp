#include "core/error.h"

#include <sstream>

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

}  // namespace radwalk
