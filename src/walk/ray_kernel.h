#pragma once
// RayKernel: the transition kernel that traces each step instead of storing F (transition_kernel.h).
//
// sample(k): a uniform point x on patch k, a cosine-weighted direction w about n_k, the ray spawn_ray(x, w)
// (ray_offset.h) traced through the Visibility. A front-face hit on patch j returns j, which happens with
// probability F_kj (the exact form factor of the geometry, up to the ray offset of ray_offset.h); a miss
// returns kEscaped and a back-face hit kBackHit (the absorbing back of a one-sided face; the visibility maps a
// two-sided face's hit to the patch of the side it arrives on, patch/patch_set.h "Sides"), both ending the walk
// (counted). So n_k = 1, and the walk needs O(N) memory.
//
// Rays are made in single precision, the precision they are traced in, straight into a RayPacket
// (ray_packet.h). Four 32-bit draws per ray, u = (next_u32 >> 8) 2^-24 in [0, 1) (a grid exact in float):
//   point      (u1, u2) as sample_patch_point draws it: a quad is the triangles (0,1,2), (0,2,3) chosen in
//              proportion to their areas (u1 rescaled), then the square-root warp
//              x = a + s u2 e_b + s (1 - u2) e_c, s = sqrt(u1), on the triangle (a, a + e_b, a + e_c);
//   direction  (u3, u4) as sample_cosine_hemisphere draws it: w = r cos(phi) t + r sin(phi) b + z n,
//              r = sqrt(u3), z = sqrt(1 - u3), phi = 2 pi u4 as q quarter turns plus theta (unit_circle):
//              w = r cos(theta) T_q + r sin(theta) T_{q+1} + z n, T_0..3 = t, b, -t, -b (the frame turned);
//   origin     spawn_ray's o = x + eps n + pull (c - x) (the ray leaves by the front: z > 0), that is
//              o = a' + s u2 e'_b + s (1 - u2) e'_c with a' = (1 - pull) a + pull c + eps n and
//              e' = (1 - pull) e (the patch shrunk about its centroid c and lifted by eps). In float (a few
//              roundings at the size of the coordinates) o is within 2 FLT_EPSILON max|coordinate| of the
//              exact o, a quarter of the offset eps >= 8 FLT_EPSILON max|coordinate| (ray_offset.h; tested).
// All that does not depend on the uniforms (a', e', the quad split, the turned frames) is precomputed per
// patch.
// Batches (kLanes = 16, walk_lockstep.h): the rays of up to 16 requests are made together, what does not
// depend on the patch (sqrt, cos, sin) vectorised over the lanes, and traced as one packet through the
// Visibility. The single sample is a batch of one, so a walk's rays and hits do not depend on how walks are
// batched.
// The row sums s_k, and so the escape probability 1 - s_k of a ray, are unknown without F (tables().s is empty).
// HE(k, j) = rho_k E_j for one extra, independent sample j (kHESampled): E[.] = (H E)_k.
#include <span>
#include <utility>
#include <vector>

#include "patch/patch_set.h"
#include "solve/problem.h"
#include "visibility/ray_packet.h"
#include "visibility/visibility.h"
#include "walk/transition_kernel.h"

namespace radwalk {

// One value per lane of a ray packet.
using LaneFloats = Eigen::Array<float, kPacketSize, 1>;
using LaneInts = Eigen::Array<int, kPacketSize, 1>;

// The angle phi = 2 pi u of u in [0, 1), lane by lane, as q quarter turns plus theta: q = round(4u) in 0..4,
// theta = (4u - q) pi / 2 in [-pi/4, pi/4], so (cos, sin)(phi) is (cos, sin)(theta) turned by q mod 4 quarter
// turns. cos and sin of theta by their Taylor polynomials, sin to theta^9 and cos to theta^8 (remainders
// below (pi/4)^11 / 11! < 2e-9 and (pi/4)^10 / 10! < 3e-8), in single precision: within 2^-22 of the exact
// values (a few float roundings), and vectorised, where std::sin and std::cos are not.
struct QuarterTurns {
  LaneInts q;
  LaneFloats cos_theta, sin_theta;
};
inline QuarterTurns unit_circle(const LaneFloats& u) {
  constexpr float kQuarterTurn = 1.57079632679489661923f;  // pi / 2
  const LaneFloats x = 4.0f * u;
  QuarterTurns r;
  r.q = (x + 0.5f).cast<int>();  // the nearest quarter turn (x >= 0: truncation rounds down)
  const LaneFloats theta = (x - r.q.cast<float>()) * kQuarterTurn, t2 = theta.square();
  r.sin_theta =
      theta * (1.0f - t2 * (1.0f / 6 - t2 * (1.0f / 120 - t2 * (1.0f / 5040 - t2 * (1.0f / 362880)))));
  r.cos_theta = 1.0f - t2 * (0.5f - t2 * (1.0f / 24 - t2 * (1.0f / 720 - t2 * (1.0f / 40320))));
  return r;
}

class RayKernel {
 public:
  static constexpr bool kHESampled = true;
  static constexpr std::size_t kLanes = kMaxLanes;
  static_assert(kLanes == kPacketSize, "one lockstep batch is one ray packet");
  // rho and E come from `problem` (F is not used and may be empty); geometry from `patches`; `visibility`
  // must outlive the kernel. Throws InputError on sizes that disagree.
  RayKernel(const RadiosityProblem& problem, const PatchSet& patches, const Visibility& visibility,
            std::vector<double> p)
      : RayKernel(problem, problem.E, patches, visibility, std::move(p)) {}
  // The same with E (N x 3) walked in place of problem.E: the shifted source of the control variate
  // (control_variate.h), with no copy of the problem.
  RayKernel(const RadiosityProblem& problem, const PatchRgb& E, const PatchSet& patches,
            const Visibility& visibility, std::vector<double> p);

  std::size_t size() const { return samplers_.size(); }
  const KernelTables& tables() const { return tables_; }

  PatchIndex sample(std::size_t k, Rng& rng, WalkCounters& counters) const {
    const SampleRequest request{k, &rng};
    PatchIndex j = kEscaped;
    sample(std::span<const SampleRequest>(&request, 1), std::span<PatchIndex>(&j, 1), counters);
    return j;
  }
  void sample(std::span<const SampleRequest> requests, std::span<PatchIndex> out,
              WalkCounters& counters) const;
  Rgb HE(std::size_t k, PatchIndex j) const {
    return j >= 0 ? Rgb(tables_.rho[k] * tables_.E[static_cast<std::size_t>(j)]) : Rgb::Zero();
  }

  // The ray of one destination sample from patch k (four draws from rng), as sample() traces it.
  Ray sample_ray(std::size_t k, Rng& rng) const;

 private:
  // Per patch, in single precision (see the top of this file): triangle t = 0, (a', a' + e'_1, a' + e'_2),
  // for u1 in [0, split) and t = 1, (a', a' + e'_2, a' + e'_3), for u1 in [split, 1), split = area(0,1,2) /
  // area (1 for a triangle), u1 rescaled to [0, 1) as (u1 - lower[t]) inv_width[t]; then the frame. 124 bytes,
  // aligned to two cache lines: a ray from k reads both, and no more.
  struct alignas(64) PatchSampler {
    Eigen::Vector3f corner;       // a' = (1 - pull) a + pull c + eps n
    Eigen::Vector3f edge[3];      // e'_1, e'_2, e'_3 (e'_3 = e'_2 for a triangle)
    float lower[2] = {0, 1};      // 0, split
    float inv_width[2] = {1, 0};  // 1 / split, 1 / (1 - split) (0 when split = 1)
    Eigen::Vector3f tangent[4];   // T_0..3 = t, b, -t, -b
    Eigen::Vector3f normal;       // n
  };

  // The rays of requests[0 .. count) (count <= kPacketSize) into `rays`, four draws from each stream.
  void make_rays(const SampleRequest* requests, std::size_t count, RayPacket& rays) const;

  const Visibility& visibility_;
  std::vector<PatchSampler> samplers_;
  KernelTables tables_;
};

}  // namespace radwalk
