// format_number: printf's %g, %e and %f, and the same text as an ostream at the same precision (the messages
// that were written through an ostringstream read the same).
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "core/format_number.h"

using namespace radwalk;

namespace {

std::string through_ostream(double x, int precision) {
  std::ostringstream s;
  s.precision(precision);
  s << x;
  return s.str();
}

}  // namespace

TEST_CASE("format_number writes printf's %g, %e and %f at the given precision", "[format_number]") {
  CHECK(format_number(0.1) == "0.1");
  CHECK(format_number(1.0 / 3.0) == "0.333333");
  CHECK(format_number(1234567.0) == "1.23457e+06");
  CHECK(format_number(2.0 / 3.0, 3) == "0.667");
  CHECK(format_number(0.01234, 2) == "0.012");
  CHECK(format_number(0.1, 17) == "0.10000000000000001");
  CHECK(format_number(1e-4, 0, NumberNotation::scientific) == "1e-04");
  CHECK(format_number(293.14999, 2, NumberNotation::fixed) == "293.15");
  CHECK(format_number(-0.0) == "-0");
  CHECK(format_number(std::numeric_limits<double>::infinity()) == "inf");
  CHECK(format_number(-std::numeric_limits<double>::infinity()) == "-inf");
  CHECK(format_number(std::numeric_limits<double>::max(), 2, NumberNotation::fixed).size() == 312);
  CHECK(format_rgb(Rgb(0.5, 1.0 / 3.0, 2.0), 4) == "(0.5, 0.3333, 2)");
  CHECK(format_rgb(Rgb(0.5, 1.0 / 3.0, 2.0)) == "(0.5, 0.333333, 2)");
}

TEST_CASE("format_number in general notation reads as an ostream writes at the same precision", "[format_number]") {
  const double values[] = {0.0, 1.0, -2.5, 1.0 / 3.0, 123456.789, 1e-300, 6.02214076e23, 1e21, 0.000123456789,
                           std::numeric_limits<double>::infinity(), std::numeric_limits<double>::denorm_min()};
  for (int precision : {1, 3, 6, 17})
    for (double x : values) {
      INFO("x = " << x << ", precision " << precision);
      CHECK(format_number(x, precision) == through_ostream(x, precision));
    }
}
