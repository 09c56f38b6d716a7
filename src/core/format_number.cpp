#include "core/format_number.h"

#include <algorithm>
#include <cstdio>

namespace radwalk {

std::string format_number(double x, int precision, NumberNotation notation) {
  const int p = std::clamp(precision, 0, 40);
  const char* format = notation == NumberNotation::scientific ? "%.*e"
                       : notation == NumberNotation::fixed    ? "%.*f"
                                                              : "%.*g";
  // Fixed notation of the largest double has 309 digits before the point; the buffer holds it and 40 after.
  char text[400];
  const int n = std::snprintf(text, sizeof text, format, p, x);
  if (n < 0) return "?";
  return std::string(text, std::size_t(std::min<int>(n, int(sizeof text) - 1)));
}

std::string format_rgb(const Rgb& c, int precision) {
  return '(' + format_number(c[0], precision) + ", " + format_number(c[1], precision) + ", " +
         format_number(c[2], precision) + ')';
}

}  // namespace radwalk
