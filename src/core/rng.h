#pragma once
// Counter-based random streams, addressed by (seed, domain, a, b) (docs/ARCHITECTURE.md, convention 5:
// reproducible random streams).
//
// Every consumer of random numbers draws from stream(seed, domain, a, b): a pure function of the user's seed, the
// consumer's own StreamDomain, and two indices the domain defines (for example patch and walk index). So
//   - the numbers a walk, a ray batch or a sample sees never depend on which thread runs it: any thread count
//     gives identical results, and a single walk can be replayed;
//   - two consumers never share a stream: the domains are disjoint by construction (below), so for example
//     form-factor row i and gathering walk 0 from patch i are independent (they would replay the same numbers if
//     both were addressed by (seed, i, 0) alone).
// The generator is PCG32 (O'Neill 2014, XSH-RR output). The address is hashed with SplitMix64 finalisers
// (mix64, a bijection of 64-bit words):
//   family = mix64(mix64(seed) ^ (domain << 48 | a)),   a < 2^48,
//   state, increment = mix64 hashes of family ^ b * 0xd1b54a32d192ed03.
// For one seed, (domain, a) -> domain << 48 | a is one-to-one for a < 2^48 and mix64 is a bijection, so different
// (domain, a) give different families; streams of one family differ in b. The list of domains, with what their
// indices mean, is in docs/ARCHITECTURE.md ("Random streams").
#include <cstdint>

namespace radwalk {

// Who draws the numbers; each value is used by exactly one consumer (docs/ARCHITECTURE.md lists them).
enum class StreamDomain : std::uint64_t {
  test = 0,            // tests' own random inputs (a, b as the test chooses)
  form_factor_row = 1, // estimate_form_factors: a = patch i (its whole row of rays), b = 0
  gather_walk = 2,     // gathering random walks: a = start patch i, b = walk index w
  shoot_particle = 3,  // shooting random walks: a = 0, b = particle index w
  patch_average = 4,   // path-traced patch averages: a = patch i, b = sample index s
  render_pixel = 5,    // path-traced images: a = pixel index y * width + x, b = sample index s
  light_particle = 6,  // light tracing (patch tallies and images): a = 0, b = particle index k
  synthetic_problem = 7,  // synthetic test problems (solve/synthetic_problem.h): a = row i, b = 0
  benchmark = 8,       // bench/ programs' own inputs
  direct_light_shift = 9,  // Sobol direct light (walk/direct_light.h): a = receiving patch j, b = replicate r
  emission_shift = 10,     // Sobol shooting, first rays (walk/stratified_emission.h): a = source patch j, b = replicate r;
                           // a = 2^47: the systematic birth offset of replicate b
  sobol_particle = 11,     // Sobol shooting, the particles' later draws: a = replicate r, b = particle index w
  measure_walk = 12,   // estimators of a measurement M = <R, B> (walk/measure_walks.h): a = 0, b = walk index
  importance_walk = 13,  // importance-driven walks (walk/importance_walk.h): a = channel c, b = walk index
  visible_direct_light = 14,  // direct light by point-to-polygon form factors (walk/direct_light.h): a = receiving
                              // patch j, b = replicate r << 32 | emitter rank k
  emitter_form_factor = 15,   // emitter columns of F (formfactor/emitter_form_factors.h): a = row i, b = emitter e
  jacobi_shift = 16,          // stochastic Jacobi (walk/stochastic_jacobi.h): a = source patch j (2^47: the birth
                              // offset; 2^46 + w: ray w's draws on the matrix kernel), b = replicate r << 32 | k
  analytic_visibility = 17,   // the visibility fraction of a patch pair (formfactor/analytic_form_factors.h): the
                              // digital shift of its point pairs; a = patch i, b = patch j (i < j)
  error_estimate = 18,        // error estimates (formfactor/sampling_factor.h, solve/error_propagation.h): a = 0 the
                              // replicated rows, a = 1 + k probe k; b = 0
  discretisation_estimate = 19,  // the fluctuation gather of the discretisation error (solve/fluctuation_gather.h): a =
                                 // patch i, b = 0
  hierarchical_direct = 20,   // the direct light of an element (hierarchy/direct_refinement.h): a = element e, b = 0
  hierarchical_jacobi = 21,   // hierarchical stochastic Jacobi (hierarchy/hierarchical_jacobi.h): the stratified
                              // emission of iteration k of replicate r, b = r << 32 | k (a as jacobi_shift's)
  hierarchical_variation = 22,  // the within-leaf variation of the radiosity (hierarchy/leaf_variation.h): a = leaf
                                // element e, b = 0 its points, 1 + q replicate q's directions and emitter points
};

// The largest first index a stream address may have (exclusive): a < 2^48.
inline constexpr std::uint64_t kStreamIndexLimit = std::uint64_t{1} << 48;

// SplitMix64 finaliser: a bijective 64-bit mix.
constexpr std::uint64_t mix64(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// The hash every stream (seed, domain, a, b) starts from (see the top of this file); a is reduced modulo 2^48.
constexpr std::uint64_t stream_family(std::uint64_t seed, StreamDomain domain, std::uint64_t a) {
  return mix64(mix64(seed) ^ (static_cast<std::uint64_t>(domain) << 48 | (a & (kStreamIndexLimit - 1))));
}

class Rng {
 public:
  // The stream of `family` (stream_family) and index b; stream() and RngFamily are the ways to get one.
  static Rng from_family(std::uint64_t family, std::uint64_t b) { return Rng(family, b); }

  // A placeholder stream (family 0), to be replaced by a real one before use (e.g. default-constructed walks).
  Rng() : Rng(0, 0) {}

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
  Rng(std::uint64_t family, std::uint64_t b) {
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

// The stream (seed, domain, a, b).
inline Rng stream(std::uint64_t seed, StreamDomain domain, std::uint64_t a, std::uint64_t b = 0) {
  return Rng::from_family(stream_family(seed, domain, a), b);
}

// The streams (seed, domain, a, b) for one (seed, domain, a) and many b, e.g. all walks started from one patch:
// the family hash is computed once. RngFamily(seed, domain, a).stream(b) == stream(seed, domain, a, b).
class RngFamily {
 public:
  RngFamily(std::uint64_t seed, StreamDomain domain, std::uint64_t a) : family_(stream_family(seed, domain, a)) {}
  Rng stream(std::uint64_t b) const { return Rng::from_family(family_, b); }

 private:
  std::uint64_t family_;
};

}  // namespace radwalk
