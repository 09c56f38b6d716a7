#include "walk/ray_kernel.h"

#include <string>

#include "core/error.h"
#include "core/sampling.h"
#include "visibility/ray_offset.h"

namespace radwalk {

RayKernel::RayKernel(const RadiosityProblem& problem, const PatchSet& patches, const Visibility& visibility,
                     std::vector<double> p)
    : patches_(patches), visibility_(visibility), eps_(ray_epsilon(patches)) {
  const std::size_t N = patches.size();
  if (static_cast<std::size_t>(problem.rho.rows()) != N || static_cast<std::size_t>(problem.E.rows()) != N ||
      p.size() != N)
    throw InputError("ray kernel: " + std::to_string(N) + " patches but rho has " +
                     std::to_string(problem.rho.rows()) + " rows, E " + std::to_string(problem.E.rows()) +
                     ", p " + std::to_string(p.size()) + ": sizes must agree");
  frames_.reserve(N);
  for (std::size_t k = 0; k < N; ++k) frames_.emplace_back(patches.normal[k]);
  // Scored stops are the roulette stops: a_k = 1 - p_k.
  std::vector<double> n(N, 1.0), a(N);
  for (std::size_t k = 0; k < N; ++k) a[k] = 1.0 - p[k];
  tables_ = make_walk_tables(problem.rho, problem.E, std::move(p), std::move(n), std::move(a));
}

PatchIndex RayKernel::sample(std::size_t k, Rng& rng, WalkCounters& counters) const {
  ++counters.steps;
  // Uniform point on patch k, cosine-weighted direction about its normal.
  const double u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform(), u4 = rng.uniform();
  const Vec3 x = sample_patch_point(patches_, k, u1, u2);
  const Vec3 w = frames_[k].to_world(sample_cosine_hemisphere(u3, u4));
  // First patch along the ray: front hit = move, anything else ends the walk.
  const Hit hit = visibility_.intersect(spawn_ray(patches_, k, x, w, eps_));
  if (hit.missed()) {
    ++counters.escapes;
    return kEscaped;
  }
  if (!hit.front) {
    ++counters.back_hits;
    return kBackHit;
  }
  return hit.patch;
}

}  // namespace radwalk
