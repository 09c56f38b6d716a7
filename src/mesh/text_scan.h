#pragma once
// Strict scanning of the text scene formats (OBJ, MTL, PLY header): each input file is read ONCE into memory and
// parsed from those bytes, with one line rule and one name rule for every statement of every format.
//
// Reading: core/input_file.h (read_input_file: regular files only, bounded).
// Line rule (for_each_line): a line ends at "\n", "\r\n" or a lone "\r"; a UTF-8 byte-order mark at the start of
// the file is skipped; a line whose last character is '\' continues on the next line (the backslash and the line
// break become one space), and the joined statement is numbered by its first line.
// Tokens (split_tokens): separated by spaces and tabs, up to a '#' comment.
// Name rule (rest_of_statement): a name (material, material library) is everything from its first token to the
// end of the statement or a '#' comment, trailing spaces and tabs removed, so "newmtl red paint" and "usemtl red
// paint" name the same material.
// Numbers: decimal only (no hex floats such as 0x1p-1, no blanks), by std::from_chars, correctly rounded; nan and inf
// parse so that callers refuse them precisely; underflow rounds to 0, overflow is "out of range". The one rule of
// every numeric field of every text input and of every numeric option value (apps/radwalk.cpp rule_number).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/input_file.h"

namespace radwalk {

// Calls visit(line_number, line) for each statement of text under the line rule above (line numbers from 1).
template <class Visit>
void for_each_line(std::string_view text, Visit&& visit);

// Tokens of a line separated by spaces and tabs, up to a '#' comment; each a view into `line`.
std::vector<std::string_view> split_tokens(std::string_view line);

// The name rule: from the start of `first` (a token of `line`, from split_tokens) to the end of the statement or a
// '#', without trailing spaces and tabs.
std::string_view rest_of_statement(std::string_view line, std::string_view first);

// What parse_number found.
enum class NumberStatus { ok, not_a_number, out_of_range };
struct ParsedNumber {
  NumberStatus status = NumberStatus::not_a_number;
  double value = 0;
};
// A double from the whole token (a leading '+' is allowed; "nan" and "inf" parse). A value below the smallest
// double rounds to 0 (or the nearest subnormal); one above the largest is out_of_range.
ParsedNumber parse_number(std::string_view token);
// parse_number's value when ok, else nothing.
std::optional<double> parse_double(std::string_view token);

// A long from the whole token (a leading '+' is allowed), or nothing.
std::optional<long> parse_long(std::string_view token);

// An integer written as an integer or as a number with a zero fractional part ("2", "2.0"), or nothing.
std::optional<long> parse_integral(std::string_view token);

// The directory part of a path including its trailing '/', or "" for a bare file name.
std::string directory_of(const std::string& path);

// The extension of a path in lower case without the dot ("" if none).
std::string lower_extension(const std::string& path);

// ---------------------------------------------------------------------------------------------------------------

template <class Visit>
void for_each_line(std::string_view text, Visit&& visit) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  long number = 0;
  std::string joined;  // a statement continued over several lines
  long joined_first = 0;
  while (!text.empty()) {
    const std::size_t end = text.find_first_of("\r\n");
    std::string_view line = text.substr(0, end);
    ++number;
    std::size_t next = end == std::string_view::npos ? text.size() : end + 1;
    if (end != std::string_view::npos && text[end] == '\r' && end + 1 < text.size() && text[end + 1] == '\n')
      ++next;
    text.remove_prefix(next);
    const bool continues = !line.empty() && line.back() == '\\';
    if (continues || !joined.empty()) {
      if (joined.empty()) joined_first = number;
      joined.append(line.substr(0, continues ? line.size() - 1 : line.size()));
      if (continues) {
        joined.push_back(' ');
        if (!text.empty()) continue;
      }
      visit(joined_first, std::string_view(joined));
      joined.clear();
      continue;
    }
    visit(number, line);
  }
}

}  // namespace radwalk
