#include "mesh/vtk_legacy_scan.h"

#include <cctype>

#include "core/error.h"

namespace radwalk {
namespace {

bool is_space(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }

}  // namespace

void LegacyScanner::skip_space() {
  while (at_ < bytes_.size() && is_space(bytes_[at_])) {
    if (bytes_[at_] == '\n') ++line_;
    ++at_;
  }
}

std::optional<LegacyScanner::Token> LegacyScanner::peek() {
  skip_space();
  if (at_ >= bytes_.size()) return std::nullopt;
  std::size_t end = at_;
  while (end < bytes_.size() && !is_space(bytes_[end])) ++end;
  return Token{bytes_.substr(at_, end - at_), line_, at_, !raw_seen_};
}

std::optional<LegacyScanner::Token> LegacyScanner::next() {
  std::optional<Token> t = peek();
  if (t) at_ += t->text.size();
  return t;
}

LegacyScanner::Token LegacyScanner::require(const std::string& what) {
  std::optional<Token> t = next();
  if (!t) refuse_here("the file ends before " + what);
  return *t;
}

std::string_view LegacyScanner::rest_of_line() {
  const std::size_t start = at_;
  std::size_t end = bytes_.find('\n', at_);
  if (end == std::string_view::npos) end = bytes_.size();
  at_ = end < bytes_.size() ? end + 1 : end;
  if (end < bytes_.size()) ++line_;
  std::string_view line = bytes_.substr(start, end - start);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return line;
}

std::string_view LegacyScanner::raw(std::size_t n, const std::string& what) {
  if (n > left())
    refuse_here(what + ": needs " + std::to_string(n) + " bytes, only " + std::to_string(left()) +
                " are left (truncated file or wrong count)");
  const std::string_view block = bytes_.substr(at_, n);
  at_ += n;
  raw_seen_ = raw_seen_ || n > 0;
  return block;
}

void LegacyScanner::skip_blank_lines() {
  while (at_ < bytes_.size() && (bytes_[at_] == ' ' || bytes_[at_] == '\r' || bytes_[at_] == '\n')) {
    if (bytes_[at_] == '\n') ++line_;
    ++at_;
  }
}

bool LegacyScanner::looking_at(std::string_view word) const {
  if (left() < word.size()) return false;
  for (std::size_t i = 0; i < word.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(bytes_[at_ + i])) != std::tolower(static_cast<unsigned char>(word[i])))
      return false;
  return true;
}

std::string LegacyScanner::place_at(long line, std::size_t byte, bool before_raw) const {
  if (before_raw) return locate(path_, line, -1, "");
  return path_ + ": at byte " + std::to_string(byte) + ": ";
}

std::string LegacyScanner::place(const Token& token) const {
  return place_at(token.line, token.byte, token.before_raw);
}
std::string LegacyScanner::place() const { return place_at(line_, at_, !raw_seen_); }

void LegacyScanner::refuse(const Token& token, const std::string& what) const {
  throw InputError(printable(place(token) + what));
}

void LegacyScanner::refuse_here(const std::string& what) const { throw InputError(printable(place() + what)); }

}  // namespace radwalk
