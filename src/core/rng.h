#pragma once
// Counter-based random streams (docs/ARCHITECTURE.md, convention 5: reproducible random streams).
//
// A stream is a pure function of (seed, a, b), e.g. (seed, patch, walk index): the numbers a walk or a ray
// batch sees never depend on which thread runs it, so any thread count gives identical results and a single
// walk can be replayed. The generator is PCG32 (O'Neill 2014, XSH-RR output); the (seed, a, b) triple is
// hashed to the PCG state and stream increment with SplitMix64 finalisers.
#include <cstdint>

namespace radwalk {

// SplitMix64 finaliser: a bijective 64-bit mix.
constexpr std::uint64_t mix64(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

class Rng {
 public:
  // The stream identified by (seed, a, b). Different triples give statistically independent streams.
  Rng(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0) : Rng(FromFamily{}, family_hash(seed, a), b) {}

  // The hash of (seed, a) that every stream (seed, a, b) starts from (see RngFamily).
  static constexpr std::uint64_t family_hash(std::uint64_t seed, std::uint64_t a) { return mix64(mix64(seed) ^ a); }
  // The stream (seed, a, b) from family_hash(seed, a): equal to Rng(seed, a, b).
  static Rng from_family(std::uint64_t family, std::uint64_t b) { return Rng(FromFamily{}, family, b); }

  // Uniform 32-bit integer.
  std::uint32_t next_u32() {
    const std::uint64_t old = state_;
    state_ = old * 6364136223846793005ULL + inc_;
    const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<std::uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }

  // Uniform double in [0, 1) with 53 random bits.
  double uniform() {
    const std::uint64_t hi = next_u32() >> 5;  // 27 bits
    const std::uint64_t lo = next_u32() >> 6;  // 26 bits
    return static_cast<double>((hi << 26) | lo) * 0x1.0p-53;
  }

  // Uniform integer in [0, n), n > 0 (Lemire's multiply-shift with rejection; unbiased).
  std::uint32_t uniform_index(std::uint32_t n) {
    std::uint64_t m = std::uint64_t(next_u32()) * n;
    auto l = static_cast<std::uint32_t>(m);
    if (l < n) {
      const std::uint32_t t = (0u - n) % n;
      while (l < t) {
        m = std::uint64_t(next_u32()) * n;
        l = static_cast<std::uint32_t>(m);
      }
    }
    return static_cast<std::uint32_t>(m >> 32);
  }

 private:
  struct FromFamily {};
  Rng(FromFamily, std::uint64_t family, std::uint64_t b) {
    const std::uint64_t h = mix64(family ^ (b * 0xd1b54a32d192ed03ULL));
    inc_ = (mix64(h ^ 0xa0761d6478bd642fULL) << 1u) | 1u;
    state_ = 0;
    next_u32();
    state_ += h;
    next_u32();
  }

  std::uint64_t state_ = 0;
  std::uint64_t inc_ = 1;
};

// The streams (seed, a, b) for one (seed, a) and many b, e.g. all walks started from one patch: the hash of
// (seed, a) is computed once. RngFamily(seed, a).stream(b) is the same stream as Rng(seed, a, b).
class RngFamily {
 public:
  RngFamily(std::uint64_t seed, std::uint64_t a) : family_(Rng::family_hash(seed, a)) {}
  Rng stream(std::uint64_t b) const { return Rng::from_family(family_, b); }

 private:
  std::uint64_t family_;
};

}  // namespace radwalk
