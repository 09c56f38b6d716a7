#pragma once
// Strict scanning of the text scene formats (OBJ, MTL, PLY header): whole-file reading, line splitting into
// whitespace-separated tokens, and number parsing that refuses what it cannot read exactly.
//
// Numbers are parsed with std::from_chars, which rounds correctly (0.73 becomes the double nearest 0.73), unlike
// the hand-written parsers of tinyobjloader (off by one ulp for 0.73) and OpenMesh (8-bit colours). NaN and
// infinity are parsed as such so that callers can reject them with a precise message.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace radwalk {

// The whole content of a file; throws InputError("PATH: cannot open ...") if it cannot be read.
std::string read_text_file(const std::string& path);

// Calls visit(line_number, line) for each line of text (line numbers start at 1; a trailing '\r' is removed).
template <class Visit>
void for_each_line(std::string_view text, Visit&& visit) {
  long number = 0;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    std::string_view line = text.substr(0, end);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    visit(++number, line);
    if (end == std::string_view::npos) break;
    text.remove_prefix(end + 1);
  }
}

// Tokens of a line separated by spaces and tabs, up to a '#' comment.
std::vector<std::string_view> split_tokens(std::string_view line);

// A double from the whole token (a leading '+' is allowed; "nan" and "inf" parse), or nothing.
std::optional<double> parse_double(std::string_view token);

// A long from the whole token (a leading '+' is allowed), or nothing.
std::optional<long> parse_long(std::string_view token);

// The directory part of a path including its trailing '/', or "" for a bare file name.
std::string directory_of(const std::string& path);

// The extension of a path in lower case without the dot ("" if none).
std::string lower_extension(const std::string& path);

}  // namespace radwalk
