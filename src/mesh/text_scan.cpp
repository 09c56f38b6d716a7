#include "mesh/text_scan.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

#include "core/error.h"

namespace radwalk {

std::vector<std::string_view> split_tokens(std::string_view line) {
  std::vector<std::string_view> tokens;
  const std::size_t comment = line.find('#');
  if (comment != std::string_view::npos) line = line.substr(0, comment);
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

std::string_view rest_of_statement(std::string_view line, std::string_view first) {
  const auto start = static_cast<std::size_t>(first.data() - line.data());
  std::string_view rest = line.substr(start);
  rest = rest.substr(0, rest.find('#'));
  while (!rest.empty() && (rest.back() == ' ' || rest.back() == '\t')) rest.remove_suffix(1);
  return rest;
}

namespace {

// A token without the leading '+' the number rules allow; nothing for "+" followed by another sign ("+-1" is
// not a number, though from_chars would read the "-1" after the '+').
std::optional<std::string_view> without_plus(std::string_view token) {
  if (token.empty() || token.front() != '+') return token;
  token.remove_prefix(1);
  if (!token.empty() && (token.front() == '-' || token.front() == '+')) return std::nullopt;
  return token;
}

// The decimal exponent of a number token's first significant digit, e with 10^e <= |value| < 10^(e + 1) (for
// "0.00123e5" 2, for "1234" 3), saturated far beyond the double range; the mantissa must not be all zeros.
long decimal_exponent(std::string_view token) {
  std::size_t i = token.empty() || token.front() != '-' ? 0 : 1;
  long position = 0;  // of the first significant digit relative to the decimal point
  bool significant = false, fraction = false;
  for (; i < token.size() && token[i] != 'e' && token[i] != 'E'; ++i) {
    const char c = token[i];
    if (c == '.') {
      fraction = true;
    } else if (!significant && c == '0') {
      if (fraction) --position;
    } else if (!significant) {
      significant = true;
      if (fraction) --position;
    } else if (!fraction && position < 100000) {
      ++position;
    }
  }
  long exponent = 0;
  if (i < token.size()) {
    const bool negative = i + 1 < token.size() && token[i + 1] == '-';
    for (std::size_t k = i + 1; k < token.size(); ++k)
      if (token[k] >= '0' && token[k] <= '9' && exponent < 100000)
        exponent = 10 * exponent + (token[k] - '0');
    if (negative) exponent = -exponent;
  }
  return std::clamp(position, -100000L, 100000L) + exponent;
}

}  // namespace

ParsedNumber parse_number(std::string_view written) {
  ParsedNumber r;
  const auto unsigned_token = without_plus(written);
  if (!unsigned_token || unsigned_token->empty()) return r;
  const std::string_view token = *unsigned_token;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), r.value);
  if (end != token.data() + token.size()) return r;
  if (ec == std::errc::result_out_of_range) {
    // from_chars reports underflow and overflow alike: underflow is a value below 1 (rounds to zero),
    // overflow one above (too large for a double), which the decimal exponent of the first significant digit
    // tells apart.
    if (decimal_exponent(token) < 0) {
      r.value = token.front() == '-' ? -0.0 : 0.0;
      r.status = NumberStatus::ok;
      return r;
    }
    r.status = NumberStatus::out_of_range;
    return r;
  }
  if (ec != std::errc()) return r;
  r.status = NumberStatus::ok;
  return r;
}

std::optional<double> parse_double(std::string_view token) {
  const ParsedNumber n = parse_number(token);
  if (n.status != NumberStatus::ok) return std::nullopt;
  return n.value;
}

std::optional<long> parse_long(std::string_view written) {
  const auto unsigned_token = without_plus(written);
  if (!unsigned_token || unsigned_token->empty()) return std::nullopt;
  const std::string_view token = *unsigned_token;
  long value = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size()) return std::nullopt;
  return value;
}

std::optional<long> parse_integral(std::string_view token) {
  if (const auto v = parse_long(token)) return v;
  const auto x = parse_double(token);
  if (!x || !std::isfinite(*x) || std::floor(*x) != *x || std::abs(*x) > 1e15) return std::nullopt;
  return static_cast<long>(*x);
}

std::string directory_of(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

std::string lower_extension(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  const std::size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
  std::string ext = path.substr(dot + 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace radwalk
