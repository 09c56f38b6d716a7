#include "walk/ray_kernel.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"

namespace radwalk {

RayKernel::RayKernel(const RadiosityProblem& problem, const PatchSet& patches, const Visibility& visibility,
                     std::vector<double> p)
    : visibility_(visibility) {
  const std::size_t N = patches.size();
  if (static_cast<std::size_t>(problem.rho.rows()) != N || static_cast<std::size_t>(problem.E.rows()) != N ||
      p.size() != N)
    throw InputError("ray kernel: " + std::to_string(N) + " patches but rho has " +
                     std::to_string(problem.rho.rows()) + " rows, E " + std::to_string(problem.E.rows()) +
                     ", p " + std::to_string(p.size()) + ": sizes must agree");
  // Per-patch sampling records (the quad split as in sample_patch_point).
  const double eps = ray_epsilon(patches);
  samplers_.resize(N);
  for (std::size_t k = 0; k < N; ++k) {
    PatchSampler& s = samplers_[k];
    s.a = patches.corner(k, 0);
    s.e1 = patches.corner(k, 1) - s.a;
    s.e2 = patches.corner(k, 2) - s.a;
    s.e3 = s.e2;
    if (patches.is_quad(k)) {
      s.e3 = patches.corner(k, 3) - s.a;
      const double a1 = s.e1.cross(s.e2).norm(), a2 = s.e2.cross(s.e3).norm();
      s.split = a1 / (a1 + a2);
      s.inv_split = 1.0 / s.split;
      s.inv_rest = s.split < 1 ? 1.0 / (1.0 - s.split) : 0.0;
    }
    s.frame = Frame(patches.normal[k]);
    s.offset = patch_ray_offset(patches, k, eps);
  }
  // Scored stops are the roulette stops: a_k = 1 - p_k.
  std::vector<double> n(N, 1.0), a(N);
  for (std::size_t k = 0; k < N; ++k) a[k] = 1.0 - p[k];
  tables_ = make_walk_tables(problem.rho, problem.E, std::move(p), std::move(n), std::move(a));
}

Ray RayKernel::ray(std::size_t k, double u1, double u2, double u3, const Eigen::Vector2d& phi) const {
  const PatchSampler& s = samplers_[k];
  // Uniform point: pick the triangle, rescale u1 to [0, 1), square-root warp.
  const bool first = u1 < s.split;
  u1 = std::min(first ? u1 * s.inv_split : (u1 - s.split) * s.inv_rest, 0x1.fffffffffffffp-1);
  const Vec3& eb = first ? s.e1 : s.e2;
  const Vec3& ec = first ? s.e2 : s.e3;
  const Vec3 x = s.a + std::sqrt(u1) * (u2 * eb + (1.0 - u2) * ec);
  // Cosine-weighted direction about the normal (sample_cosine_hemisphere), and the offset origin.
  const double r = std::sqrt(u3);
  const Vec3 w = s.frame.to_world(Vec3(r * phi.x(), r * phi.y(), std::sqrt(1.0 - u3)));
  return spawn_ray(s.offset, x, w);
}

Ray RayKernel::sample_ray(std::size_t k, Rng& rng) const {
  // Four uniforms from one 32-bit draw each (the same as roulette_uniform).
  const double u1 = roulette_uniform(rng), u2 = roulette_uniform(rng), u3 = roulette_uniform(rng);
  return ray(k, u1, u2, u3, unit_circle(roulette_uniform(rng)));
}

void RayKernel::sample(std::span<const SampleRequest> requests, std::span<PatchIndex> out,
                       WalkCounters& counters) const {
  Ray rays[kMaxLanes];
  Hit hits[kMaxLanes];
  double u1[kMaxLanes], u2[kMaxLanes], u3[kMaxLanes], u4[kMaxLanes];
  Eigen::Vector2d phi[kMaxLanes];
  for (std::size_t base = 0; base < requests.size(); base += kMaxLanes) {
    const std::size_t m = std::min(kMaxLanes, requests.size() - base);
    const SampleRequest* request = requests.data() + base;
    // The rays as sample_ray makes them, in phases over the lanes (the uniforms, then cos and sin, then the
    // geometry), so that the lanes' independent dependency chains overlap.
    for (std::size_t r = 0; r < m; ++r) {
      Rng& rng = *request[r].rng;
      u1[r] = roulette_uniform(rng);
      u2[r] = roulette_uniform(rng);
      u3[r] = roulette_uniform(rng);
      u4[r] = roulette_uniform(rng);
    }
    for (std::size_t r = 0; r < m; ++r) phi[r] = unit_circle(u4[r]);
    for (std::size_t r = 0; r < m; ++r) rays[r] = ray(request[r].k, u1[r], u2[r], u3[r], phi[r]);
    // First patch along each ray: front hit = move, anything else ends the walk.
    visibility_.intersect(rays, hits, m);
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
    counters.steps += static_cast<long>(m);
  }
}

}  // namespace radwalk
