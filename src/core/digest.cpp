#include "core/digest.h"

namespace radwalk {

void Digest::bytes(const unsigned char* p, std::size_t n) {
  std::uint64_t h = h_;
  for (std::size_t k = 0; k < n; ++k) h = (h ^ p[k]) * 0x100000001b3ULL;
  h_ = h;
}

void Digest::add(std::uint64_t v) {
  unsigned char b[8];
  for (int k = 0; k < 8; ++k) b[k] = static_cast<unsigned char>(v >> (8 * k));
  bytes(b, 8);
}

void Digest::add(std::string_view s) {
  add(static_cast<std::uint64_t>(s.size()));
  bytes(reinterpret_cast<const unsigned char*>(s.data()), s.size());
}

std::string Digest::hex() const {
  static const char* kDigits = "0123456789abcdef";
  std::string s(16, '0');
  for (int k = 0; k < 16; ++k) s[15 - k] = kDigits[(h_ >> (4 * k)) & 15];
  return s;
}

}  // namespace radwalk
