#include "pathtrace/render.h"

#include <algorithm>
#include <optional>
#include <string>

#include "core/distributed.h"
#include "core/error.h"
#include "core/moments.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/timer.h"
#include "pathtrace/facet_geometry.h"

namespace radwalk {

RenderResult render_image(const PatchSet& patches, const Visibility& visibility, const Camera& camera,
                          const RenderOptions& options) {
  if (options.spp < 2) throw InputError("render: spp must be >= 2 (got " + std::to_string(options.spp) + ")");
  const Timer timer;
  const PinholeCamera pinhole(camera, options.width, options.height);
  const FacetGeometry facets(patches);
  const PathIntegrator integrator(patches, facets, visibility, options.integrator);
  RenderResult result;
  result.mean = RgbImage(options.width, options.height);
  result.se = RgbImage(options.width, options.height);
  result.spp = options.spp;

  // One work item per image row; per-row counters are summed in row order.
  std::vector<PathCounters> row_counters(static_cast<std::size_t>(options.height));
  // Over MPI each rank renders a block of rows (pixels have their own streams), then all share them.
  const std::vector<distributed::Range> rows = distributed::all_blocks(static_cast<std::size_t>(options.height));
  const distributed::Range mine = rows[static_cast<std::size_t>(distributed::rank())];
  std::optional<Progress> progress;
  if (options.progress) progress.emplace("rendering", mine.size());
  const double m = static_cast<double>(options.spp);
  // Radiances are summed and squared as L / scale (core/moments.h moment_scale: a power of two, exact), so that
  // an emission up to pi 1e300 gives a finite mean and standard error.
  const double scale = moment_scale(patches.max_emission()), inverse_scale = 1 / scale;
  parallel_for(
      mine.size(),
      [&](std::size_t local) {
        const std::size_t row = mine.begin + local;
        const int py = static_cast<int>(row);
        PathCounters& counters = row_counters[row];
        for (int px = 0; px < options.width; ++px) {
          const auto pixel = static_cast<std::uint64_t>(py) * options.width + px;
          Rgb sum = Rgb::Zero(), sum2 = Rgb::Zero();
          for (long s = 0; s < options.spp; ++s) {
            if (s % 1024 == 0) throw_if_cancelled();  // a row can hold width x spp paths (core/cancellation.h)
            Rng rng = stream(options.seed, StreamDomain::render_pixel, pixel, static_cast<std::uint64_t>(s));
            const double u = rng.uniform(), v = rng.uniform();
            const Rgb L = integrator.radiance(pinhole.generate_ray(px + u, py + v), rng, counters) * inverse_scale;
            sum += L;
            sum2 += L * L;
          }
          const auto [mean, var] = mean_and_variance(sum, sum2, m);
          result.mean.at(px, py) = mean * scale;
          result.se.at(px, py) = (var / m).sqrt() * scale;
        }
        if (progress) progress->advance(1);
      },
      1);
  if (progress) progress->finish();
  if (distributed::size() > 1) {
    distributed::share_blocks(row_counters, rows);
    std::vector<distributed::Range> pixels;  // the rows' pixels
    const auto w = static_cast<std::size_t>(options.width);
    for (const distributed::Range& r : rows) pixels.push_back({r.begin * w, r.end * w});
    distributed::share_blocks(result.mean.pixels, pixels);
    distributed::share_blocks(result.se.pixels, pixels);
  }
  for (const auto& c : row_counters) {
    result.rays += c.rays;
    result.vertices += c.vertices;
  }
  result.seconds = timer.seconds();
  return result;
}

}  // namespace radwalk
