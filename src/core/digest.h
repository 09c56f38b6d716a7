#pragma once
// Digest: a 64-bit FNV-1a hash of a byte sequence (Fowler, Noll, Vo: h <- (h xor byte) * 0x100000001b3, from the
// offset basis 0xcbf29ce484222325). Not cryptographic: it tells apart the inputs of different runs (the run id,
// apps/run_metadata.h), it does not resist a forger.
#include <cstdint>
#include <string>
#include <string_view>

namespace radwalk {

class Digest {
 public:
  // Adds the bytes of `bytes`, preceded by their length (so that "ab" + "c" and "a" + "bc" differ).
  void add(std::string_view bytes);
  // Adds the 8 bytes of v (little-endian).
  void add(std::uint64_t v);
  std::uint64_t value() const { return h_; }
  // value() as 16 lower-case hexadecimal digits.
  std::string hex() const;

 private:
  void bytes(const unsigned char* p, std::size_t n);
  std::uint64_t h_ = 0xcbf29ce484222325ULL;
};

}  // namespace radwalk
