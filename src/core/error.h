#pragma once
// Errors radwalk reports to users. Every message is one line that names where the problem is. The program maps
// them to exit codes: InputError 2 (the user can fix it), NumericalError 3, InternalError and anything else 4.
#include <stdexcept>
#include <string>
#include <string_view>

namespace radwalk {

// Bad input (a file, a face, an option): the program prints what() and exits non-zero.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A numerical problem a solver detected and refuses to hide (divergence, singular system).
class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A broken internal invariant: a bug in radwalk, not the user's input (core/check.h throws it; exit code 4).
class InternalError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

// `text` made safe to print in a one-line message or a JSON string: control characters, DEL and bytes that are
// not valid UTF-8 become \xNN escapes; everything else (valid UTF-8 included) is kept.
std::string printable(std::string_view text);

// A number for a message: the shortest text that reads back to the same double ("200", "1e-50", "0.73"), never
// "0.000000" for a small value or "200.000000" for a whole one.
std::string number_text(double x);

// "FILE:LINE: face F: WHAT" with the parts that are known (line <= 0 or face < 0 are left out).
std::string locate(const std::string& file, long line, long face, const std::string& what);

}  // namespace radwalk
