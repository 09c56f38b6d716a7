#pragma once
// What a message quotes of a line, token or name read from a file: at most kExcerptChars bytes of it, so that a
// malformed line of a megabyte is named by its start instead of being echoed whole into a one-line error.
#include <cstddef>
#include <string>
#include <string_view>

namespace radwalk {

inline constexpr std::size_t kExcerptChars = 80;

// printable(text) (core/error.h) when text has at most kExcerptChars bytes, else its first kExcerptChars bytes
// (cut before a UTF-8 character, never inside one), made printable, then "...".
std::string excerpt(std::string_view text);

}  // namespace radwalk
