#pragma once
// Stratified emission for the Sobol shooting (random_walk_solver.h, WalkSampler::sobol): n particles allocated to
// the source patches systematically in proportion to their power, and each patch's particles given the points of
// a randomised Sobol sequence (core/sobol.h) for their first ray.
//
// Source radiosity S (the emission E, or the direct light D when it is computed apart: direct_light.h), power
// Phi_j = A_j sum_c |S_jc| (a source may be negative in places: an unbiased estimate of the direct light in
// full shadow, direct_light.h; its particles then carry negative weights), pi_j = Phi_j / Phi, cdf_j = sum_{k<j} pi_k. Replicate r draws one offset U in [0, 1)
// (the first draw of stream (seed, emission_shift, 2^47, r)); particle w = 0 .. n-1 is born on the patch j with
// cdf_j <= (w + U) / n < cdf_{j+1}, so patch j gets first_{j+1} - first_j particles, first_j = ceil(n cdf_j - U)
// (clamped to [0, n]): floor or ceil of n pi_j, and exactly n pi_j in expectation over U. Each carries the weight
// W0_j = A_j S_j / pi_j (per channel); so sum_w W0_{j(w)} f_{j(w)} / n is unbiased for sum_j A_j S_j f_j for any f.
// Particle w of patch j has rank q = w - first_j; its first ray takes Sobol point q shifted by the words of
// stream (seed, emission_shift, j, r) (point (u0, u1) and cosine direction (u2, u3) as the ray kernel makes them),
// so a patch's first rays are stratified over its area and its hemisphere together.
#include <array>
#include <cstdint>
#include <vector>

#include "core/rng.h"
#include "core/sobol.h"
#include "core/types.h"

namespace radwalk {

class StratifiedEmission {
 public:
  // S and area of the N patches, n >= 1 particles. Throws InputError on a non-finite S or a negative area.
  // `domain`: the stream domain of the shifts and the offset (emission_shift for the Sobol shooting; the
  // stochastic Jacobi iterations use their own, stochastic_jacobi.h).
  StratifiedEmission(const PatchRgb& S, const Eigen::VectorXd& area, long n, std::uint64_t seed,
                     std::uint64_t replicate, StreamDomain domain = StreamDomain::emission_shift);

  double power() const { return power_; }  // Phi (0: nothing to shoot)
  long particles() const { return n_; }
  // The patch particle w is born on (w < n, power() > 0).
  std::size_t patch_of(long w) const;
  // Its weight W0_j and its first ray's four uniforms.
  const Rgb& weight(std::size_t j) const { return W0_[j]; }
  std::array<float, 4> first_uniforms(long w, std::size_t j) const;
  // first_j, j = 0 .. N (first_N = n).
  const std::vector<long>& first() const { return first_; }

 private:
  long n_ = 0;
  double power_ = 0;
  std::vector<long> first_;
  std::vector<Rgb> W0_;
  std::vector<SobolShift> shift_;
};

}  // namespace radwalk
