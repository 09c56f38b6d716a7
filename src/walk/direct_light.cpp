#include "walk/direct_light.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "core/check.h"
#include "core/parallel.h"
#include "core/rng.h"
#include "core/sobol.h"
#include "formfactor/point_polygon_form_factor.h"
#include "formfactor/visible_form_factor.h"
#include "visibility/ray_offset.h"

namespace radwalk {

namespace {

// The digital shift of Sobol points: the four words of stream (seed, domain, a, b).
SobolShift shift_of(std::uint64_t seed, StreamDomain domain, std::uint64_t a, std::uint64_t b) {
  Rng rng = stream(seed, domain, a, b);
  SobolShift shift;
  for (auto& w : shift.word) w = rng.next_u32();
  return shift;
}

// D = 0 and no ray: the estimate of a scene without emitters.
DirectLight no_direct_light(const PatchSet& patches) {
  DirectLight none;
  none.D.setZero(static_cast<Eigen::Index>(patches.size()), 3);
  return none;
}

// The frame of both ray estimators: for every receiving patch j (rho_j > 0 in some channel), in parallel (one
// work item per receiver, so the result does not depend on the thread count),
//   D_j = rho_j .* S_j / divisor,   S_j = receive(j, rays_j),
// where receive returns the estimator's sum for j (nullopt: no light reaches j, D_j = 0) and adds the shadow rays
// it traced to rays_j; D.rays is their total.
template <class Receive>
DirectLight per_receiver(const RadiosityProblem& problem, const PatchSet& patches, double divisor, Receive&& receive) {
  const std::size_t N = patches.size();
  DirectLight out = no_direct_light(patches);
  std::vector<long> rays(N, 0);
  parallel_for(
      N,
      [&](std::size_t j) {
        const auto row = static_cast<Eigen::Index>(j);
        if (!(problem.rho.row(row).maxCoeff() > 0)) return;
        const std::optional<Rgb> sum = receive(j, rays[j]);
        if (sum) out.D.row(row) = (problem.rho.row(row).transpose() * *sum / divisor).transpose();
      },
      1);
  for (long n : rays) out.rays += n;
  return out;
}

// The checks both ray estimators start with: sizes that agree, at least one sample per receiver.
void check_direct_light_inputs(const RadiosityProblem& problem, const PatchSet& patches, long samples_per_patch) {
  RADWALK_CHECK_EQ(static_cast<std::size_t>(problem.E.rows()), patches.size());
  RADWALK_CHECK(samples_per_patch >= 1);
}

}  // namespace

DirectLight estimate_direct_light(const RadiosityProblem& problem, const PatchSet& patches,
                                  const Visibility& visibility, long samples_per_patch, std::uint64_t seed,
                                  std::uint64_t replicate) {
  check_direct_light_inputs(problem, patches, samples_per_patch);
  const std::size_t N = patches.size();
  // The emitters and the CDF of their powers Phi_e.
  std::vector<std::size_t> emitter;
  std::vector<double> cdf{0.0};
  for (std::size_t e = 0; e < N; ++e) {
    const double phi = problem.area(static_cast<Eigen::Index>(e)) * problem.E.row(static_cast<Eigen::Index>(e)).sum();
    if (phi > 0) {
      emitter.push_back(e);
      cdf.push_back(cdf.back() + phi);
    }
  }
  if (emitter.empty()) return no_direct_light(patches);
  const double Phi = cdf.back();
  const double eps = ray_epsilon(patches);
  return per_receiver(problem, patches, static_cast<double>(samples_per_patch), [&](std::size_t j, long& rays) {
    const SobolShift shift = shift_of(seed, StreamDomain::direct_light_shift, j, replicate);
    const PatchRayOffset offset = patch_ray_offset(patches, j, eps);
    const Vec3& nj = patches.normal[j];
    constexpr std::size_t kBatch = 64;
    std::vector<Ray> batch;
    std::vector<Rgb> value;    // E_e G A_e Phi / Phi_e of each traced ray
    std::vector<double> dist;  // |y - x|
    std::vector<Hit> hits(kBatch);
    Rgb sum = Rgb::Zero();
    auto trace = [&] {
      visibility.intersect(batch.data(), hits.data(), batch.size());
      for (std::size_t q = 0; q < batch.size(); ++q)
        if (hits[q].missed() || hits[q].t >= dist[q] * (1 - 1e-5) - 4 * eps) sum += value[q];
      rays += static_cast<long>(batch.size());
      batch.clear();
      value.clear();
      dist.clear();
    };
    for (long s = 0; s < samples_per_patch; ++s) {
      const auto u = sobol_point(static_cast<std::uint32_t>(s), shift);
      const Vec3 x = sample_patch_point(patches, j, u[0], u[1]);
      // The emitter of u2 and u2 rescaled within its interval.
      const double u2 = double(u[2]) * Phi;
      const auto it = std::upper_bound(cdf.begin() + 1, cdf.end(), u2);
      const auto m = static_cast<std::size_t>(std::min<std::ptrdiff_t>(it - cdf.begin() - 1,
                                                                         static_cast<std::ptrdiff_t>(emitter.size()) - 1));
      const std::size_t e = emitter[m];
      if (e == j) continue;
      const double phi_e = cdf[m + 1] - cdf[m];
      const double v = std::clamp((u2 - cdf[m]) / phi_e, 0.0, 0x1.fffffffffffffp-1);
      const Vec3 y = sample_patch_point(patches, e, v, u[3]);
      const Vec3 d = y - x;
      const double r2 = d.squaredNorm();
      if (!(r2 > 0)) continue;
      const double r = std::sqrt(r2);
      const Vec3 w = d / r;
      const double cos_x = nj.dot(w), cos_y = -patches.normal[e].dot(w);
      if (cos_x <= 0 || cos_y <= 0) continue;
      const double G = cos_x * cos_y / (kPi * r2);
      const auto erow = static_cast<Eigen::Index>(e);
      value.push_back(problem.E.row(erow).transpose() * (G * problem.area(erow) * Phi / phi_e));
      dist.push_back(r);
      batch.push_back(spawn_ray(offset, x, w));
      if (batch.size() == kBatch) trace();
    }
    if (!batch.empty()) trace();
    return std::optional<Rgb>(sum);
  });
}

DirectLight estimate_visible_direct_light(const RadiosityProblem& problem, const PatchSet& patches,
                                          const Visibility& visibility, long samples_per_patch, std::uint64_t seed,
                                          std::uint64_t replicate) {
  check_direct_light_inputs(problem, patches, samples_per_patch);
  const std::size_t N = patches.size();
  std::vector<std::size_t> emitter;
  for (std::size_t e = 0; e < N; ++e)
    if (problem.E.row(static_cast<Eigen::Index>(e)).maxCoeff() > 0) emitter.push_back(e);
  if (emitter.empty()) return no_direct_light(patches);
  const VisibleFormFactor visible(patches, visibility);
  // S_j = sum_e E_e F_je (an irradiance: divisor 1).
  return per_receiver(problem, patches, 1.0, [&](std::size_t j, long& rays) -> std::optional<Rgb> {
    std::vector<std::size_t> seen;  // emitter ranks
    for (std::size_t k = 0; k < emitter.size(); ++k)
      if (emitter[k] != j && patch_may_see(patches, j, emitter[k])) seen.push_back(k);
    if (seen.empty()) return std::nullopt;
    const long M = std::max<long>(1, samples_per_patch / static_cast<long>(seen.size()));
    Rgb irradiance = Rgb::Zero();
    for (std::size_t k : seen) {
      const SobolShift shift = shift_of(seed, StreamDomain::visible_direct_light, j, replicate << 32 | k);
      const double F = visible.estimate(j, emitter[k], M, shift, rays);
      irradiance += F * problem.E.row(static_cast<Eigen::Index>(emitter[k])).transpose();
    }
    return irradiance;
  });
}

PatchRgb exact_direct_light(const RadiosityProblem& problem) {
  RADWALK_CHECK_EQ(problem.F.rows(), problem.E.rows());
  const PatchRgb FE = (problem.F.cast<double>() * problem.E.matrix()).array();
  return problem.rho * FE;
}

}  // namespace radwalk
