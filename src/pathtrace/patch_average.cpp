#include "pathtrace/patch_average.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "core/distributed.h"
#include "core/error.h"
#include "core/moments.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/timer.h"
#include "patch/patch_set.h"
#include "pathtrace/facet_geometry.h"

namespace radwalk {

namespace {
// Work item = (patch, block of samples); the split depends only on spp, never on the thread count.
constexpr long kBlock = 256;

struct Partial {
  Rgb sum = Rgb::Zero();    // sum of rho E_irr_hat
  Rgb sum2 = Rgb::Zero();   // sum of its squares
  PathCounters counters;
};
}  // namespace

Solution estimate_patch_averages(const PatchSet& patches, const Visibility& visibility,
                                 const PatchAverageOptions& options) {
  return estimate_patch_averages(patches, FacetGeometry(patches), visibility, options);
}

Solution estimate_patch_averages(const PatchSet& patches, const SurfaceGeometry& geometry,
                                 const Visibility& visibility, const PatchAverageOptions& options) {
  if (options.spp < 2) throw InputError("path tracer: spp must be >= 2 (got " + std::to_string(options.spp) + ")");
  const Timer timer;
  const PathIntegrator integrator(patches, geometry, visibility, options.integrator);
  const std::size_t n = patches.size();
  const auto blocks = static_cast<std::size_t>((options.spp + kBlock - 1) / kBlock);
  std::vector<Partial> parts(n * blocks);
  // Over MPI each rank traces a block of the work items (their own streams), then all share them.
  const std::vector<distributed::Range> ranges = distributed::all_blocks(parts.size());
  const distributed::Range mine = ranges[static_cast<std::size_t>(distributed::rank())];
  std::optional<Progress> progress;
  if (options.progress) progress.emplace("path tracing patches", mine.size());

  // Samples: x uniform on the patch, then an irradiance estimate at x.
  parallel_for(
      mine.size(),
      [&](std::size_t local) {
        const std::size_t item = mine.begin + local;
        const std::size_t i = item / blocks;
        const long s0 = static_cast<long>(item % blocks) * kBlock;
        const long s1 = std::min(options.spp, s0 + kBlock);
        Partial& p = parts[item];
        const RngFamily samples(options.seed, StreamDomain::patch_average, i);
        for (long s = s0; s < s1; ++s) {
          Rng rng = samples.stream(static_cast<std::uint64_t>(s));
          const double u1 = rng.uniform(), u2 = rng.uniform();
          const auto patch = static_cast<PatchIndex>(i);
          const Vec3 x = geometry.sample_point(patch, u1, u2);
          const Rgb y = patches.rho[i] * integrator.irradiance(patch, x, rng, p.counters);
          p.sum += y;
          p.sum2 += y * y;
        }
        if (progress) progress->advance(1);
      },
      1);
  if (progress) progress->finish();
  distributed::share_blocks(parts, ranges);

  // Combine blocks in order; unbiased per-sample variance.
  Solution sol;
  sol.method = std::string("pathtrace-") + to_string(options.integrator.kind);
  sol.B.resize(static_cast<Eigen::Index>(n), 3);
  sol.B_se.resize(static_cast<Eigen::Index>(n), 3);
  sol.var.resize(static_cast<Eigen::Index>(n), 3);
  PathCounters total;
  const double m = static_cast<double>(options.spp);
  for (std::size_t i = 0; i < n; ++i) {
    Rgb sum = Rgb::Zero(), sum2 = Rgb::Zero();
    for (std::size_t b = 0; b < blocks; ++b) {
      sum += parts[i * blocks + b].sum;
      sum2 += parts[i * blocks + b].sum2;
      total.add(parts[i * blocks + b].counters);
    }
    const auto [mean, var] = mean_and_variance(sum, sum2, m);
    const auto r = static_cast<Eigen::Index>(i);
    sol.B.row(r) = (patches.E[i] + mean).transpose();
    sol.var.row(r) = var.transpose();
    sol.B_se.row(r) = (var / m).sqrt().transpose();
  }
  sol.status = SolveStatus::converged;
  sol.walks = static_cast<long>(n) * options.spp;
  sol.steps = total.vertices;
  sol.seconds = timer.seconds();
  sol.message = "path traced " + std::to_string(options.spp) + " samples per patch";
  if (options.integrator.max_depth > 0)
    sol.message += " (biased: paths capped at " + std::to_string(options.integrator.max_depth) + " bounces)";
  sol.info["spp"] = m;
  sol.info["rays"] = static_cast<double>(total.rays);
  sol.info["escapes"] = static_cast<double>(total.escapes);
  sol.info["rays_per_second"] = sol.seconds > 0 ? static_cast<double>(total.rays) / sol.seconds : 0.0;
  sol.info["rr_depth"] = options.integrator.rr_depth;
  sol.info["max_depth"] = options.integrator.max_depth;
  return sol;
}

}  // namespace radwalk
