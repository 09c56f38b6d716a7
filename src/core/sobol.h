#pragma once
// Sobol points in up to kSobolDimensions = 4 dimensions, randomised by a random digital shift
// (docs/ARCHITECTURE.md, "Random streams": the shifts come from their own stream domains).
//
// Point r (r = 0, 1, ...) of the Sobol sequence, coordinate d, as a 32-bit fraction:
//   x_d(r) = XOR over the bits b_k of r of v_{d,k}      (v_{d,k} the direction numbers, k = 0 .. 31),
// the point in [0, 1)^4 being x_d(r) 2^-32. Dimension 0 is the van der Corput sequence (v_{0,k} = 2^(31-k));
// dimensions 1..3 come from the primitive polynomials x + 1, x^2 + x + 1 and x^3 + x + 1 with initial numbers
// m = (1), (1, 3), (1, 3, 1) (Joe and Kuo's table, the first rows; Bratley and Fox's recurrence
// v_k = a_1 v_{k-1} ^ ... ^ a_{s-1} v_{k-s+1} ^ v_{k-s} ^ (v_{k-s} >> s)).
// Properties the tests check: dimensions (0, 1) form a (0, 2)-sequence in base 2 (every elementary interval
// [a 2^-i, (a+1) 2^-i) x [b 2^-j, (b+1) 2^-j) of area 2^-m, i + j = m, holds exactly one of the points
// 2^m q .. 2^m (q+1) - 1); every single dimension is a (0, 1)-sequence (each interval of length 2^-m holds one of
// 2^m consecutive aligned points).
// Randomisation (random digital shift, XOR with a uniform 32-bit word per dimension): every shifted point is
// uniform on the grid 2^-32 (so an estimate averaging a function over the points is unbiased), and the
// stratification properties above are kept (XOR with a constant permutes the elementary intervals).
#include <array>
#include <cstdint>

namespace radwalk {

inline constexpr int kSobolDimensions = 4;

namespace detail {
// The direction numbers v_{d,k}, k = 0..31 (see the top of this file).
constexpr std::array<std::array<std::uint32_t, 32>, kSobolDimensions> sobol_directions() {
  struct Poly {
    int s;             // degree
    std::uint32_t a;   // the inner coefficients a_1 .. a_{s-1} as bits (a_1 the highest)
    std::uint32_t m[3];
  };
  constexpr Poly polys[kSobolDimensions - 1] = {{1, 0, {1, 0, 0}}, {2, 1, {1, 3, 0}}, {3, 1, {1, 3, 1}}};
  std::array<std::array<std::uint32_t, 32>, kSobolDimensions> v{};
  for (int k = 0; k < 32; ++k) v[0][k] = std::uint32_t{1} << (31 - k);
  for (int d = 1; d < kSobolDimensions; ++d) {
    const Poly& p = polys[d - 1];
    for (int k = 0; k < p.s && k < 32; ++k) v[d][k] = p.m[k] << (31 - k);
    for (int k = p.s; k < 32; ++k) {
      std::uint32_t x = v[d][k - p.s] ^ (v[d][k - p.s] >> p.s);
      for (int i = 1; i < p.s; ++i)
        if ((p.a >> (p.s - 1 - i)) & 1u) x ^= v[d][k - i];
      v[d][k] = x;
    }
  }
  return v;
}
inline constexpr auto kSobolV = sobol_directions();
}  // namespace detail

// Coordinate d (0 .. kSobolDimensions - 1) of Sobol point r, unshifted, as a 32-bit fraction.
constexpr std::uint32_t sobol_u32(std::uint32_t r, int d) {
  std::uint32_t x = 0;
  const auto& v = detail::kSobolV[static_cast<std::size_t>(d)];
  for (std::size_t k = 0; r != 0; ++k, r >>= 1) x ^= v[k] & (0u - (r & 1u));  // branch-free: bit k of r selects v_k
  return x;
}

// A random digital shift: one uniform 32-bit word per dimension.
struct SobolShift {
  std::array<std::uint32_t, kSobolDimensions> word{};
};

// Point r shifted, coordinate by coordinate, as floats on the grid 2^-24 in [0, 1) (the ray kernel's uniforms).
inline std::array<float, kSobolDimensions> sobol_point(std::uint32_t r, const SobolShift& shift) {
  std::array<float, kSobolDimensions> u{};
  for (int d = 0; d < kSobolDimensions; ++d)
    u[static_cast<std::size_t>(d)] =
        static_cast<float>((sobol_u32(r, d) ^ shift.word[static_cast<std::size_t>(d)]) >> 8) * 0x1.0p-24f;
  return u;
}

}  // namespace radwalk
