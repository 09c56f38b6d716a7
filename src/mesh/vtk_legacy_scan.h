#pragma once
// The bytes of a legacy VTK file (.vtk) as its reader walks them: white-space separated tokens (VTK's `>>`, white
// space as C's isspace), the rest of a line, and blocks of raw bytes (the data of a BINARY file, which follow the
// line of their section header). Every read is bounded by the bytes left: a block longer than what is left, or a
// token asked for at the end of the file, is one InputError naming the file, the place and what was expected.
//
// Places: "FILE:LINE:" for what lies before the first block of raw bytes (all of an ASCII file, a BINARY file's
// header and first section); after raw bytes, line numbers would count newline bytes inside binary numbers, so a
// place is "FILE: at byte N:" instead (N from 0).
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace radwalk {

class LegacyScanner {
 public:
  struct Token {
    std::string_view text;
    long line = 0;         // the line the token is on (meaningful when before_raw)
    std::size_t byte = 0;  // its first byte's offset in the file
    bool before_raw = true;  // read before any raw bytes: its line is meaningful
  };

  LegacyScanner(std::string path, std::string_view bytes) : path_(std::move(path)), bytes_(bytes) {}

  // The next token after white space, or nothing at the end of the file.
  std::optional<Token> next();
  // The next token, or a refusal "ends before WHAT" at the end of the file.
  Token require(const std::string& what);
  // The next token without taking it.
  std::optional<Token> peek();

  // The rest of the current line (without its '\n' and a '\r' before it), and the scan moves past the '\n'.
  std::string_view rest_of_line();
  // Whether the file ends here (nothing left but nothing at all).
  bool at_end() const { return at_ >= bytes_.size(); }

  // The next n bytes, raw; refused unless n bytes are left ("WHAT: needs N bytes, only M are left").
  std::string_view raw(std::size_t n, const std::string& what);

  // Moves past spaces, '\r' and '\n' only (VTK's skip of blank lines after an array, before METADATA).
  void skip_blank_lines();
  // Whether the bytes at the scan position start with `word`, in any case (ASCII letters).
  bool looking_at(std::string_view word) const;

  std::size_t left() const { return bytes_.size() - at_; }
  std::size_t position() const { return at_; }

  // The place of a token, or of the scan position, in the form described above, and a refusal there.
  std::string place(const Token& token) const;
  std::string place() const;
  [[noreturn]] void refuse(const Token& token, const std::string& what) const;
  [[noreturn]] void refuse_here(const std::string& what) const;

  const std::string& path() const { return path_; }
  bool text_only() const { return !raw_seen_; }

 private:
  std::string place_at(long line, std::size_t byte, bool before_raw) const;
  void skip_space();

  std::string path_;
  std::string_view bytes_;
  std::size_t at_ = 0;
  long line_ = 1;
  bool raw_seen_ = false;
};

}  // namespace radwalk
