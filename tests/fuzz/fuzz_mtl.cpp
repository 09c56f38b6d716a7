// Fuzz harness: the MTL scanner alone (mesh/mtl.h, scan_mtl_text and material_from_mtl) and the number rule
// every text format shares (mesh/text_scan.h, parse_number and parse_long).
//
// Input: the bytes of one MTL file, "fuzz/library.mtl".
// Contract: scan_mtl_text returns the newmtl blocks or throws InputError; material_from_mtl maps any block.
// Oracles:
//   (a) a refusal is one line of printable UTF-8 that starts with the file's path;
//   (scan) every block has a non-empty name without line breaks, '#' or surrounding blanks (the name rule),
//       the file's path, increasing lines; every number it holds is finite; its Material has the block's
//       name, Kd, Ke and Ks, and finite Ni, roughness and metallic;
//   (numbers) on every blank-separated token of every line: a token of the decimal grammar
//       [+-]? (digits [. digits?] | . digits) ([eE] [+-]? digits)? is what strtod makes of it: the same
//       double, out_of_range where strtod overflows, 0 or strtod's subnormal where it underflows; any other
//       token is not a number (parse_number, but for inf and nan); parse_long agrees with strtoll on tokens
//       [+-]? digits and refuses every other token.
#include <cerrno>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <string>

#include "fuzz_support.h"
#include "mesh/mtl.h"
#include "mesh/text_scan.h"

using namespace radwalk;
using namespace radwalk::fuzz;

namespace {

const std::string kMtlPath = "fuzz/library.mtl";

bool digit(char c) {
  return c >= '0' && c <= '9';
}

// The decimal grammar above, matched by hand (an independent reading of what a number is).
bool decimal_number(std::string_view s) {
  std::size_t i = 0;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
  std::size_t before = 0, after = 0;
  while (i < s.size() && digit(s[i])) ++i, ++before;
  if (i < s.size() && s[i] == '.') {
    ++i;
    while (i < s.size() && digit(s[i])) ++i, ++after;
  }
  if (before + after == 0) return false;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    std::size_t exponent = 0;
    while (i < s.size() && digit(s[i])) ++i, ++exponent;
    if (exponent == 0) return false;
  }
  return i == s.size();
}

bool integer_token(std::string_view s) {
  std::size_t i = s.empty() || (s[0] != '+' && s[0] != '-') ? 0 : 1;
  if (i == s.size()) return false;
  for (; i < s.size(); ++i)
    if (!digit(s[i])) return false;
  return true;
}

void check_integer_rule(std::string_view token) {
  const std::string t(token);
  const auto index = parse_long(token);
  if (!integer_token(token)) {
    RADWALK_FUZZ_CHECK(!index, "'" + printable(t) + "' is not an integer but parsed as one");
    return;
  }
  errno = 0;
  const long long wanted = std::strtoll(t.c_str(), nullptr, 10);
  if (errno == ERANGE)
    RADWALK_FUZZ_CHECK(!index, "'" + printable(t) + "' overflows a long, read as one");
  else
    RADWALK_FUZZ_CHECK(index && *index == wanted, "'" + printable(t) + "' is not read as its integer");
}

void check_number_rule(std::string_view token) {
  const std::string t(token);
  const ParsedNumber got = parse_number(token);
  if (!decimal_number(token)) {
    // "inf" and "nan" (any case, with the forms strtod takes) parse as such, for callers to refuse precisely.
    if (got.status == NumberStatus::ok)
      RADWALK_FUZZ_CHECK(!std::isfinite(got.value),
                         "'" + printable(t) + "' is not a decimal number but parsed as one");
    return;
  }
  errno = 0;
  const double want = std::strtod(t.c_str(), nullptr);
  const bool overflow = errno == ERANGE && std::isinf(want);
  const bool underflow = errno == ERANGE && !overflow;
  if (overflow) {
    RADWALK_FUZZ_CHECK(got.status == NumberStatus::out_of_range,
                       "'" + printable(t) + "' overflows, not reported");
    return;
  }
  RADWALK_FUZZ_CHECK(got.status == NumberStatus::ok, "'" + printable(t) + "' is a number, refused");
  if (underflow)
    RADWALK_FUZZ_CHECK(got.value == 0 || got.value == want,
                       "'" + printable(t) + "' underflows to a wrong value");
  else
    RADWALK_FUZZ_CHECK(got.value == want && std::signbit(got.value) == std::signbit(want),
                       "'" + printable(t) + "' is not read as the nearest double");
}

bool finite(const std::optional<Rgb>& c) {
  return !c || c->allFinite();
}
bool finite(const std::optional<double>& x) {
  return !x || std::isfinite(*x);
}

void check_entries(const std::vector<MtlEntry>& entries) {
  long previous = 0;
  for (const MtlEntry& e : entries) {
    const std::string name = "material '" + printable(e.name) + "'";
    RADWALK_FUZZ_CHECK(!e.name.empty() && e.name.find_first_of("\r\n#") == std::string::npos &&
                           e.name.front() != ' ' && e.name.front() != '\t' && e.name.back() != ' ' &&
                           e.name.back() != '\t',
                       name + ": not a name under the name rule");
    RADWALK_FUZZ_CHECK(e.file == kMtlPath && e.line > previous, name + ": file or line");
    previous = e.line;
    RADWALK_FUZZ_CHECK(finite(e.Kd) && finite(e.Ke) && finite(e.Ks) && finite(e.Ni) && finite(e.Ns) &&
                           finite(e.Pr) && finite(e.Pm),
                       name + ": a non-finite number was accepted");
    const Material m = material_from_mtl(e);
    RADWALK_FUZZ_CHECK(m.name == e.name && m.file == e.file && m.line == e.line,
                       name + ": name, file or line lost");
    RADWALK_FUZZ_CHECK((m.Kd == e.Kd.value_or(Rgb::Zero())).all() &&
                           (m.Ke == e.Ke.value_or(Rgb::Zero())).all() &&
                           (m.Ks == e.Ks.value_or(Rgb::Zero())).all(),
                       name + ": Kd, Ke or Ks not as written");
    RADWALK_FUZZ_CHECK(std::isfinite(m.Ni) && std::isfinite(m.roughness) && std::isfinite(m.metallic),
                       name + ": non-finite Ni, roughness or metallic");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text = as_text(data, size);
  for_each_line(text, [](long, std::string_view line) {
    for (const std::string_view token : split_tokens(line)) {
      check_number_rule(token);
      check_integer_rule(token);
    }
  });
  std::vector<MtlEntry> entries;
  if (accepts([&] { entries = scan_mtl_text(kMtlPath, text); }, {kMtlPath})) check_entries(entries);
  return 0;
}
