#include "mesh/vtk_legacy_array.h"

#include <cctype>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

#include "core/error.h"
#include "core/excerpt.h"
#include "mesh/text_scan.h"

namespace radwalk {
namespace {

enum class Kind { bit, signed_int, unsigned_int, real, string, variant };

struct TypeInfo {
  const char* name;
  Kind kind;
  int size;  // bytes a value in BINARY (0: not fixed)
  double least, most;  // the range of an integer type
};

constexpr double kInt64Least = -9223372036854775808.0, kInt64Most = 9223372036854775807.0;
constexpr double kUInt64Most = 18446744073709551615.0;

// The legacy format's types (vtkDataWriter's names; vtkIdType is written as a 4-byte int, char is signed here).
const TypeInfo kTypes[] = {
    {"bit", Kind::bit, 0, 0, 1},
    {"char", Kind::signed_int, 1, -128, 127},
    {"signed_char", Kind::signed_int, 1, -128, 127},
    {"unsigned_char", Kind::unsigned_int, 1, 0, 255},
    {"short", Kind::signed_int, 2, -32768, 32767},
    {"unsigned_short", Kind::unsigned_int, 2, 0, 65535},
    {"int", Kind::signed_int, 4, -2147483648.0, 2147483647.0},
    {"unsigned_int", Kind::unsigned_int, 4, 0, 4294967295.0},
    {"long", Kind::signed_int, 8, kInt64Least, kInt64Most},
    {"unsigned_long", Kind::unsigned_int, 8, 0, kUInt64Most},
    {"vtkidtype", Kind::signed_int, 4, -2147483648.0, 2147483647.0},
    {"vtktypeint64", Kind::signed_int, 8, kInt64Least, kInt64Most},
    {"vtktypeuint64", Kind::unsigned_int, 8, 0, kUInt64Most},
    {"float", Kind::real, 4, 0, 0},
    {"double", Kind::real, 8, 0, 0},
    {"string", Kind::string, 0, 0, 0},
    {"utf8_string", Kind::string, 0, 0, 0},
    {"variant", Kind::variant, 0, 0, 0},
};

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

const TypeInfo* find_type(std::string_view name) {
  const std::string l = lower(name);
  for (const TypeInfo& t : kTypes)
    if (l == t.name) return &t;
  return nullptr;
}

// The big-endian word of `size` bytes at p.
std::uint64_t big_endian(const char* p, int size) {
  std::uint64_t v = 0;
  for (int i = 0; i < size; ++i) v = (v << 8) | static_cast<unsigned char>(p[i]);
  return v;
}

// A BINARY value of type t at p, as VTK stores it, as a double.
double binary_value(const TypeInfo& t, const char* p) {
  const std::uint64_t w = big_endian(p, t.size);
  if (t.kind == Kind::real) {
    if (t.size == 4) {
      const auto bits = static_cast<std::uint32_t>(w);
      float f;
      std::memcpy(&f, &bits, 4);
      return f;
    }
    double d;
    std::memcpy(&d, &w, 8);
    return d;
  }
  if (t.kind == Kind::unsigned_int) return static_cast<double>(w);
  // Two's complement of `size` bytes: sign-extended.
  const int bits = 8 * t.size;
  if (bits == 64) return static_cast<double>(static_cast<std::int64_t>(w));
  const std::uint64_t sign = std::uint64_t{1} << (bits - 1);
  const std::int64_t v = static_cast<std::int64_t>(w & (sign - 1)) - static_cast<std::int64_t>(w & sign);
  return static_cast<double>(v);
}

// A whole number written in decimal (a leading '+' allowed), as a double: int64 values exactly, uint64 values
// above 2^63 too (rounded as VTK's GetComponent rounds them); nothing for anything else.
std::optional<double> parse_whole(std::string_view token) {
  if (const std::optional<long> v = parse_long(token)) return static_cast<double>(*v);
  std::string_view digits = token;
  if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
  unsigned long long u = 0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), u);
  if (digits.empty() || error != std::errc() || end != digits.data() + digits.size()) return std::nullopt;
  return static_cast<double>(u);
}

// VTK's variant type codes (vtkType.h) that its legacy reader converts.
bool known_variant_type(long t) {
  static const long kCodes[] = {2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 13, 15, 16, 17};
  for (long c : kCodes)
    if (t == c) return true;
  return false;
}

// The METADATA block VTK's writer may put after an array (vtkDataReader::ReadArray): after blank lines, a line
// starting with METADATA, then lines up to a blank one; COMPONENT_NAMES is followed by one line a component.
void skip_metadata(LegacyScanner& scan, std::int64_t components) {
  scan.skip_blank_lines();
  if (!scan.looking_at("metadata")) return;
  scan.rest_of_line();
  while (!scan.at_end()) {
    const std::string line = lower(scan.rest_of_line());
    if (line.empty()) break;
    if (line.compare(0, 15, "component_names") == 0)
      for (std::int64_t c = 0; c < components && !scan.at_end(); ++c) scan.rest_of_line();
  }
}

}  // namespace

bool is_legacy_type(std::string_view name) { return find_type(name) != nullptr; }

std::string decode_legacy_string(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '%' && i + 2 < text.size() + 0 && std::isxdigit(static_cast<unsigned char>(text[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(text[i + 2]))) {
      out.push_back(static_cast<char>(std::stoi(std::string(text.substr(i + 1, 2)), nullptr, 16)));
      i += 2;
    } else {
      out.push_back(text[i]);
    }
  }
  return out;
}

std::int64_t read_legacy_count(LegacyScanner& scan, const std::string& what, std::int64_t least, std::int64_t most) {
  const LegacyScanner::Token t = scan.require(what);
  const std::optional<long> n = parse_long(t.text);
  if (!n || *n < least || *n > most)
    scan.refuse(t, what + ": '" + excerpt(t.text) + "' is not a whole number from " + std::to_string(least) +
                       " to " + std::to_string(most));
  return *n;
}

LegacyArray read_legacy_array(LegacyScanner& scan, const LegacyScanner::Token& type, std::int64_t tuples,
                              std::int64_t components, bool binary, bool keep, const std::string& what) {
  const TypeInfo* t = find_type(type.text);
  if (!t)
    scan.refuse(type, what + " of type '" + excerpt(type.text) +
                          "': not one of VTK's legacy types (float, double, int, vtktypeint64, string, ...)");
  LegacyArray a;
  a.type = t->name;
  a.numeric = t->kind != Kind::string && t->kind != Kind::variant;
  a.integer = t->kind == Kind::bit || t->kind == Kind::signed_int || t->kind == Kind::unsigned_int;
  // The count, bounded by the bytes left before anything is sized by it (the product in doubles: exact whenever
  // it is below the bytes left, which are below 2^53).
  const double count = static_cast<double>(tuples) * static_cast<double>(components);
  const double left = static_cast<double>(scan.left());
  double least_bytes = 0;  // what `count` values take at least
  if (binary && t->kind == Kind::bit)
    least_bytes = std::ceil(count / 8);
  else if (binary && t->size > 0)
    least_bytes = count * t->size;
  else if (t->kind == Kind::variant)
    least_bytes = 4 * count - 1;  // "T X" and a separator each
  else if (t->kind == Kind::string)
    least_bytes = binary ? count : count - 1;  // a length byte each; a line each
  else
    least_bytes = 2 * count - 1;  // a digit and a separator each, but the last
  if (least_bytes > left)
    scan.refuse(type, what + " declares " + number_text(count) + " values of type " + t->name + ", more than the " +
                          std::to_string(scan.left()) + " bytes left can hold (truncated file or wrong count)");
  const auto n = static_cast<std::size_t>(count);
  if (keep && a.numeric) a.numbers.reserve(n);
  if (keep && !a.numeric) a.strings.reserve(n);

  if (t->kind == Kind::variant) {
    for (std::size_t i = 0; i < n; ++i) {
      const LegacyScanner::Token code = scan.require(what + "'s values");
      const std::optional<long> c = parse_long(code.text);
      if (!c || !known_variant_type(*c))
        scan.refuse(code, what + ": '" + excerpt(code.text) + "' is not a variant type VTK reads");
      const LegacyScanner::Token text = scan.require(what + "'s values");
      if (keep) a.strings.push_back(decode_legacy_string(text.text));
    }
  } else if (t->kind == Kind::string) {
    scan.rest_of_line();  // the header's line
    for (std::size_t i = 0; i < n; ++i) {
      if (binary) {
        const std::string_view first = scan.raw(1, what + ": string " + std::to_string(i) + "'s length");
        const auto top = static_cast<unsigned char>(first[0]) >> 6;
        const int size = top == 3 ? 1 : top == 2 ? 2 : top == 1 ? 4 : 8;
        std::string word(first);
        if (size > 1) word += scan.raw(static_cast<std::size_t>(size - 1), what + ": string " + std::to_string(i) + "'s length");
        std::uint64_t length = big_endian(word.data(), size);
        if (size < 8) length &= (std::uint64_t{1} << (8 * size - 2)) - 1;
        if (length > scan.left())
          scan.refuse_here(what + ": string " + std::to_string(i) + " of " + std::to_string(length) +
                           " bytes, more than the " + std::to_string(scan.left()) + " bytes left");
        const std::string_view s = scan.raw(static_cast<std::size_t>(length), what);
        if (keep) a.strings.emplace_back(s);
      } else {
        if (scan.at_end())
          scan.refuse_here(what + ": the file ends before its string " + std::to_string(i) + " of " +
                           std::to_string(n));
        const std::string_view s = scan.rest_of_line();
        if (keep) a.strings.push_back(decode_legacy_string(s));
      }
    }
  } else if (binary) {
    if (n > 0) {
      scan.rest_of_line();  // the header's line
      const std::size_t bytes = t->kind == Kind::bit ? (n + 7) / 8 : n * static_cast<std::size_t>(t->size);
      const std::string_view block = scan.raw(bytes, what);
      if (keep) {
        for (std::size_t i = 0; i < n; ++i)
          a.numbers.push_back(t->kind == Kind::bit
                                  ? ((static_cast<unsigned char>(block[i / 8]) >> (7 - i % 8)) & 1)
                                  : binary_value(*t, block.data() + i * static_cast<std::size_t>(t->size)));
      }
    }
  } else {
    for (std::size_t i = 0; i < n; ++i) {
      const std::optional<LegacyScanner::Token> next = scan.next();
      if (!next) scan.refuse(type, what + " ends before its " + std::to_string(n) + " values");
      const LegacyScanner::Token v = *next;
      double x = 0;
      if (a.integer) {
        const std::optional<double> w = parse_whole(v.text);
        const double lo = t->kind == Kind::bit ? kInt64Least : t->least;
        const double hi = t->kind == Kind::bit ? kInt64Most : t->most;
        if (!w || *w < lo || *w > hi)
          scan.refuse(v, what + ": '" + excerpt(v.text) + "' is not a whole number of type " + t->name);
        x = t->kind == Kind::bit ? (*w != 0 ? 1 : 0) : *w;
      } else {
        const ParsedNumber p = parse_number(v.text);
        if (p.status != NumberStatus::ok || (t->size == 4 && std::isfinite(p.value) && std::fabs(p.value) > FLT_MAX))
          scan.refuse(v, what + ": '" + excerpt(v.text) + "' is not a number of type " + t->name);
        x = t->size == 4 ? static_cast<double>(static_cast<float>(p.value)) : p.value;
      }
      if (keep) a.numbers.push_back(x);
    }
  }
  skip_metadata(scan, components);
  return a;
}

}  // namespace radwalk
