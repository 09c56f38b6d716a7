#pragma once
// RayKernel: the transition kernel that traces each step instead of storing F (transition_kernel.h).
//
// sample(k): a uniform point x on patch k, a cosine-weighted direction w about n_k, the ray spawn_ray(x, w)
// (ray_offset.h) traced through the Visibility. A front-face hit on patch j returns j, which happens with
// probability F_kj (the exact form factor of the geometry, up to the ray offset of ray_offset.h); a miss returns
// kEscaped and a back-face hit kBackHit, both ending the walk (counted). So n_k = 1, and the walk needs O(N)
// memory. Four 32-bit uniforms per ray, u = next_u32 / 2^32 (a grid of 2^-32, far finer than the single precision
// the ray is traced in): (u1, u2) for the point as sample_patch_point draws it (a quad is the triangles (0,1,2),
// (0,2,3) chosen in proportion to their areas, then the square-root warp), (u3, u4) for the direction as
// sample_cosine_hemisphere draws it, with (cos, sin) of 2 pi u4 from unit_circle. All that does not depend on the
// uniforms (corners as edge vectors, the quad split probability, the frame, the ray offset) is precomputed per patch.
// Batches (kLanes = 16, walk_lockstep.h): the rays of all requests go through the Visibility's batch intersect,
// one Embree packet of 16. The single sample is a batch of one, so a walk's rays and hits do not depend on how
// walks are batched.
// Scored stops for gathering absorption are the roulette stops only (a_k = 1 - p_k): the escape probability
// 1 - s_k is unknown without F, so an escape scores 0 (still unbiased).
// HE(k, j) = rho_k E_j for one extra, independent sample j (kHESampled): E[.] = (H E)_k.
#include <cmath>
#include <span>
#include <vector>

#include "core/sampling.h"
#include "patch/patch_set.h"
#include "solve/problem.h"
#include "visibility/ray_offset.h"
#include "visibility/visibility.h"
#include "walk/transition_kernel.h"

namespace radwalk {

// (cos 2 pi u, sin 2 pi u) for u in [0, 1), within 1e-11 of the exact values: reduction to the nearest quarter turn,
// theta = 2 pi (u - q / 4) in [-pi/4, pi/4], then the Taylor polynomials of sin (to theta^11) and cos (to theta^12),
// whose remainders are below (pi/4)^13 / 13! < 1e-11. A third of the instructions of std::sin and std::cos, and far
// more accurate than the single precision the ray direction is traced in.
inline Eigen::Vector2d unit_circle(double u) {
  const double x = 4.0 * u;
  const int q = static_cast<int>(x + 0.5);  // the nearest quarter turn, 0..4 (x >= 0: truncation rounds down)
  const double theta = (x - q) * (0.5 * kPi), t2 = theta * theta, t4 = t2 * t2, t8 = t4 * t4;
  // Estrin's scheme (pairs of terms, then powers t4, t8): a shorter dependency chain than Horner's.
  const double s = theta * ((1 - t2 * (1.0 / 6)) + t4 * (1.0 / 120 - t2 * (1.0 / 5040)) +
                            t8 * (1.0 / 362880 - t2 * (1.0 / 39916800)));
  const double c = (1 - t2 * 0.5) + t4 * (1.0 / 24 - t2 * (1.0 / 720)) +
                   t8 * ((1.0 / 40320 - t2 * (1.0 / 3628800)) + t4 * (1.0 / 479001600));
  switch (q & 3) {
    case 0: return {c, s};
    case 1: return {-s, c};
    case 2: return {-c, -s};
    default: return {s, -c};
  }
}

class RayKernel {
 public:
  static constexpr bool kEscapeScores = false;
  static constexpr bool kHESampled = true;
  static constexpr std::size_t kLanes = kMaxLanes;
  // rho and E come from `problem` (F is not used and may be empty); geometry from `patches`; `visibility` must
  // outlive the kernel. Throws InputError on sizes that disagree.
  RayKernel(const RadiosityProblem& problem, const PatchSet& patches, const Visibility& visibility,
            std::vector<double> p);

  std::size_t size() const { return samplers_.size(); }
  double survival(std::size_t k) const { return tables_.p[k]; }
  double row_scale(std::size_t /*k*/) const { return 1.0; }
  const WalkTables& tables() const { return tables_; }

  PatchIndex sample(std::size_t k, Rng& rng, WalkCounters& counters) const {
    const SampleRequest request{k, &rng};
    PatchIndex j = kEscaped;
    sample(std::span<const SampleRequest>(&request, 1), std::span<PatchIndex>(&j, 1), counters);
    return j;
  }
  void sample(std::span<const SampleRequest> requests, std::span<PatchIndex> out, WalkCounters& counters) const;
  Rgb HE(std::size_t k, PatchIndex j) const {
    return j >= 0 ? Rgb(tables_.rho[k] * tables_.E[static_cast<std::size_t>(j)]) : Rgb::Zero();
  }

  // The ray of one destination sample from patch k (four uniforms from rng), as sample() traces it.
  Ray sample_ray(std::size_t k, Rng& rng) const;

 private:
  // Per patch: x = a + s (u2 e_b + (1 - u2) e_c), s = sqrt(u1), on the triangle (a, a + e_b, a + e_c): (e1, e2)
  // with probability `split`, else (e2, e3); then the frame and the ray offset.
  struct PatchSampler {
    Vec3 a, e1, e2, e3;    // corner 0 and the edges to corners 1, 2, 3 (e3 = e2 for a triangle)
    double split = 1;      // area(0,1,2) / area of the patch (1 for a triangle)
    double inv_split = 1;  // 1 / split
    double inv_rest = 0;   // 1 / (1 - split) (0 when split = 1)
    Frame frame{Vec3::UnitZ()};
    PatchRayOffset offset;
  };

  // The ray from patch k for the uniforms (u1, u2, u3) and (cos, sin) = unit_circle(u4).
  Ray ray(std::size_t k, double u1, double u2, double u3, const Eigen::Vector2d& phi) const;

  const Visibility& visibility_;
  std::vector<PatchSampler> samplers_;
  WalkTables tables_;
};

}  // namespace radwalk
