#include "core/excerpt.h"

#include "core/error.h"

namespace radwalk {

std::string excerpt(std::string_view text) {
  if (text.size() <= kExcerptChars) return printable(text);
  std::size_t cut = kExcerptChars;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xc0) == 0x80) --cut;  // a continuation byte
  std::string out = printable(text.substr(0, cut));
  out.append("...");
  return out;
}

}  // namespace radwalk
