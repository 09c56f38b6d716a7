#include "walk/ray_kernel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/check.h"
#include "core/error.h"
#include "core/sampling.h"
#include "visibility/ray_offset.h"

namespace radwalk {
namespace {

// A uniform number in [0, 1) on the grid 2^-24 from one 32-bit draw: exact in single precision.
float uniform_float(Rng& rng) {
  return static_cast<float>(rng.next_u32() >> 8) * 0x1.0p-24f;
}

// sqrt lane by lane, correctly rounded (Eigen's Array::sqrt is an rsqrt approximation under EIGEN_FAST_MATH,
// whose last bits depend on the CPU); vectorised (sqrtps) thanks to -fno-math-errno (CMakeLists.txt).
LaneFloats lane_sqrt(const LaneFloats& x) {
  LaneFloats r;
  for (Eigen::Index l = 0; l < x.size(); ++l) r[l] = std::sqrt(x[l]);
  return r;
}

}  // namespace

RayKernel::RayKernel(const RadiosityProblem& problem, const PatchRgb& E, const PatchSet& patches,
                     const Visibility& visibility, std::vector<double> p)
    : visibility_(visibility) {
  const std::size_t N = patches.size();
  RADWALK_CHECK_EQ(static_cast<std::size_t>(problem.rho.rows()), N);  // patches, rho, E and p agree in size
  RADWALK_CHECK_EQ(static_cast<std::size_t>(E.rows()), N);
  RADWALK_CHECK_EQ(p.size(), N);
  // Per-patch sampling records, in double and then rounded: the quad split as in sample_patch_point, the
  // corner and edges shrunk about the centroid by (1 - pull) and lifted by eps n as spawn_ray moves a point.
  const double eps = ray_epsilon(patches);
  samplers_.resize(N);
  for (std::size_t k = 0; k < N; ++k) {
    PatchSampler& s = samplers_[k];
    const PatchRayOffset offset = patch_ray_offset(patches, k, eps);
    const double shrink = 1.0 - offset.pull;
    const Vec3& a = patches.corner(k, 0);
    const Vec3 e1 = patches.corner(k, 1) - a, e2 = patches.corner(k, 2) - a;
    const Vec3 e3 = patches.is_quad(k) ? Vec3(patches.corner(k, 3) - a) : e2;
    s.corner = (shrink * a + offset.pull * offset.centroid + offset.normal_eps).cast<float>();
    s.edge[0] = (shrink * e1).cast<float>();
    s.edge[1] = (shrink * e2).cast<float>();
    s.edge[2] = (shrink * e3).cast<float>();
    if (patches.is_quad(k)) {
      const double a1 = e1.cross(e2).norm(), a2 = e2.cross(e3).norm(), split = a1 / (a1 + a2);
      s.lower[1] = static_cast<float>(split);
      s.inv_width[0] = static_cast<float>(1.0 / split);
      s.inv_width[1] = split < 1 ? static_cast<float>(1.0 / (1.0 - split)) : 0.0f;
    }
    const Frame frame(patches.normal[k]);
    s.tangent[0] = frame.t.cast<float>();
    s.tangent[1] = frame.b.cast<float>();
    s.tangent[2] = -s.tangent[0];
    s.tangent[3] = -s.tangent[1];
    s.normal = frame.n.cast<float>();
  }
  // n_k = 1; the row sums are not known.
  tables_ = make_kernel_tables(problem.rho, E, std::move(p), std::vector<double>(N, 1.0), {});
}

void RayKernel::make_rays(const SampleRequest* requests, std::size_t count, RayPacket& rays) const {
  constexpr float kBelowOne = 0x1.fffffep-1f;
  // Step 1, per ray: the four uniforms, the triangle t of the point and u1 rescaled to [0, 1) within it (no
  // branch: t is 0 or 1 at random for a quad). Lanes past `count` keep u = 0 (computed, never traced).
  LaneFloats u1 = LaneFloats::Zero(), u2 = LaneFloats::Zero(), u3 = LaneFloats::Zero(),
             u4 = LaneFloats::Zero();
  int triangle[kPacketSize];
  for (std::size_t l = 0; l < count; ++l) {
    const PatchSampler& p = samplers_[requests[l].k];
    float given[4];
    if (requests[l].u) {  // the caller's uniforms (SampleRequest::u), nothing drawn
      std::copy(requests[l].u, requests[l].u + 4, given);
    } else {
      Rng& rng = *requests[l].rng;
      for (float& g : given) g = uniform_float(rng);
    }
    const float u = given[0];
    const int t = static_cast<int>(u >= p.lower[1]);
    triangle[l] = t;
    u1[l] = std::min((u - p.lower[t]) * p.inv_width[t], kBelowOne);
    u2[l] = given[1];
    u3[l] = given[2];
    u4[l] = given[3];
  }
  // Step 2, all lanes at once: the weights of the edges, s u2 and s (1 - u2), and the direction in the frame
  // turned by q quarter turns, (r cos theta, r sin theta, z).
  const LaneFloats s = lane_sqrt(u1), wb = s * u2, wc = s - wb;
  const LaneFloats r = lane_sqrt(u3), z = lane_sqrt(1.0f - u3);
  const QuarterTurns phi = unit_circle(u4);
  const LaneFloats wx = r * phi.cos_theta, wy = r * phi.sin_theta;
  // Step 3, per ray: into the patch's geometry.
  rays.count = count;
  for (std::size_t l = 0; l < count; ++l) {
    const PatchSampler& p = samplers_[requests[l].k];
    const int t = triangle[l], q = phi.q[l] & 3;
    const Eigen::Vector3f o = p.corner + wb[l] * p.edge[t] + wc[l] * p.edge[t + 1];
    const Eigen::Vector3f w = wx[l] * p.tangent[q] + wy[l] * p.tangent[(q + 1) & 3] + z[l] * p.normal;
    rays.org_x[l] = o.x();
    rays.org_y[l] = o.y();
    rays.org_z[l] = o.z();
    rays.dir_x[l] = w.x();
    rays.dir_y[l] = w.y();
    rays.dir_z[l] = w.z();
    rays.tmax[l] = std::numeric_limits<float>::infinity();
  }
}

Ray RayKernel::sample_ray(std::size_t k, Rng& rng) const {
  const SampleRequest request{k, &rng};
  RayPacket rays;
  make_rays(&request, 1, rays);
  return rays.ray(0);
}

void RayKernel::sample(std::span<const SampleRequest> requests, std::span<PatchIndex> out,
                       WalkCounters& counters) const {
  RayPacket rays;
  Hit hits[kPacketSize];
  for (std::size_t base = 0; base < requests.size(); base += kPacketSize) {
    const std::size_t m = std::min(kPacketSize, requests.size() - base);
    make_rays(requests.data() + base, m, rays);
    // First patch along each ray: front hit = move, anything else ends the walk.
    visibility_.intersect(rays, hits);
    for (std::size_t r = 0; r < m; ++r) {
      PatchIndex j = hits[r].patch;
      if (hits[r].missed()) {
        ++counters.escapes;
        j = kEscaped;
      } else if (!hits[r].front) {
        ++counters.back_hits;
        j = kBackHit;
      }
      out[base + r] = j;
    }
    // The walks read these patches' records next (their roulette, weights and next ray): ask for the kernel's
    // own (the ray's two cache lines, rho; a walk asks for its estimator's, walk_lockstep.h) now, so
    // that the cache misses of the 16 lanes overlap instead of coming one by one (at large N every table access
    // is a miss). A hint only: no effect on any value.
    for (std::size_t r = 0; r < m; ++r) {
      const PatchIndex j = out[base + r];
      if (j < 0) continue;
      const auto k = static_cast<std::size_t>(j);
      __builtin_prefetch(&samplers_[k]);
      __builtin_prefetch(reinterpret_cast<const char*>(&samplers_[k]) + 64);
      __builtin_prefetch(&tables_.rho[k]);
    }
    counters.steps += static_cast<long>(m);
  }
}

}  // namespace radwalk
