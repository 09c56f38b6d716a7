#include "mesh/text_scan.h"

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

ParsedNumber parse_number(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  ParsedNumber r;
  if (token.empty()) return r;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), r.value);
  if (end != token.data() + token.size()) return r;
  if (ec == std::errc::result_out_of_range) {
    // from_chars reports underflow and overflow alike: underflow is a value that rounds to (nearly) zero.
    bool nonzero_digit = false, exponent = false, negative_exponent = false;
    for (char c : token) {
      if (c == 'e' || c == 'E') exponent = true;
      else if (exponent && c == '-') negative_exponent = true;
      else if (!exponent && c >= '1' && c <= '9') nonzero_digit = true;
    }
    if (negative_exponent || !nonzero_digit) {
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

std::optional<long> parse_long(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return std::nullopt;
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
