#include "pathtrace/patch_average.h"

#include <algorithm>
#include <array>
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
// Work item = (patch, block of samples); the split depends only on spp, never on the thread count. An item's
// sums add its samples in sample order, and a patch's sums add its items in order: the items fix the result's
// bits.
constexpr long kBlock = 256;
// Items are traced in tasks of consecutive items (in the order patch, block) of about total / 512 samples, at
// least kTaskSamples and at most kMaxTaskSamples (unless one item has more), kLanes paths in flight, so that the ray batches stay full even at a few
// samples per patch. How items are grouped into tasks changes no value: each sample draws from its own stream.
constexpr long kTaskSamples = 1024, kMaxTaskSamples = 65536;
constexpr std::size_t kLanes = 32;
// Items in flight at once (their sums, 48 bytes each): the memory of the estimate is O(kWaveItems + patches),
// whatever the sample count.
constexpr std::size_t kWaveItems = std::size_t(1) << 15;


// One item of a task: samples [s0, s1) of patch i, the task's samples first .. first + s1 - s0 - 1.
struct Item {
  std::size_t patch = 0;
  long s0 = 0, s1 = 0;
  std::size_t first = 0;
};

// The samples of consecutive items, kLanes paths in lockstep, their rays traced in batches
// (PathIntegrator::trace_batch); out[k] = the sums of item k, its samples' Y = rho_i E_irr_hat(x) added in sample
// order once all have finished.
void trace_items(const PatchSet& patches, const SurfaceGeometry& geometry, const PathIntegrator& integrator,
                 const std::vector<Item>& items, std::uint64_t seed, double inverse_scale, CentralMoments4* out,
                 PathCounters& counters) {
  using Path = PathIntegrator::Path;
  if (items.empty()) return;
  const std::size_t count = items.back().first + static_cast<std::size_t>(items.back().s1 - items.back().s0);
  std::vector<Rgb> Y(count, Rgb::Zero());
  // Sample w of the task, started: x uniform on its patch (two draws), then the irradiance path at x.
  std::size_t at = 0;  // the item of the last sample started (samples start in order)
  auto make = [&](std::size_t w) {
    while (at + 1 < items.size() && w >= items[at + 1].first) ++at;
    const Item& item = items[at];
    const RngFamily samples(seed, StreamDomain::patch_average, item.patch);
    Rng rng = samples.stream(static_cast<std::uint64_t>(item.s0) + (w - item.first));
    const double u1 = rng.uniform(), u2 = rng.uniform();
    const auto patch = static_cast<PatchIndex>(item.patch);
    const Vec3 x = geometry.sample_point(patch, u1, u2);
    return integrator.start_irradiance(patch, x, rng, counters);
  };
  std::array<Path, kLanes> path;
  std::array<std::size_t, kLanes> index{};
  std::array<std::size_t, kLanes> patch_of{};
  std::size_t next = 0, active = 0;
  auto finish = [&](std::size_t lane) {
    Y[index[lane]] = patches.rho[patch_of[lane]] * (kPi * path[lane].L());
  };
  // Starts samples in order in `lane` until one waits for rays (true) or none is left (false).
  auto fill = [&](std::size_t lane) {
    while (next < count) {
      index[lane] = next;
      path[lane] = make(next++);
      patch_of[lane] = items[at].patch;
      if (!path[lane].done()) return true;
      finish(lane);
    }
    return false;
  };
  while (active < kLanes && fill(active)) ++active;
  std::array<Path*, kLanes> batch;
  while (active > 0) {
    for (std::size_t r = 0; r < active; ++r) batch[r] = &path[r];
    integrator.trace_batch(batch.data(), active, counters);
    // A finished path's lane takes the next sample or, when none is left, the last lane's path.
    for (std::size_t r = 0; r < active;) {
      if (!path[r].done()) {
        ++r;
        continue;
      }
      finish(r);
      if (fill(r)) {
        ++r;
        continue;
      }
      --active;
      if (r < active) {
        path[r] = path[active];
        index[r] = index[active];
        patch_of[r] = patch_of[active];
      }
    }
  }
  for (std::size_t k = 0; k < items.size(); ++k) {
    const std::size_t b = items[k].first, e = b + static_cast<std::size_t>(items[k].s1 - items[k].s0);
    for (std::size_t w = b; w < e; ++w) Y[w] *= inverse_scale;  // exact: a power of two
    out[k] = CentralMoments4::of(Y.data() + b, e - b);
  }
}
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
  const std::size_t item_count = n * blocks;
  const long block_samples = std::min(options.spp, kBlock);
  const long task_samples =
      std::clamp<long>((static_cast<long>(n) * options.spp + 511) / 512, kTaskSamples, kMaxTaskSamples);
  const auto per_task = static_cast<std::size_t>(std::max<long>(1, task_samples / block_samples));
  const std::size_t tasks = (item_count + per_task - 1) / per_task;
  // The tasks run in waves of at most kWaveItems items; a wave's sums are added to its patches' totals in item
  // order, so every patch adds its items in the same order as one pass over all items would.
  const std::size_t wave_tasks = std::max<std::size_t>(1, kWaveItems / per_task);
  const double inverse_scale = 1 / moment_scale(patches.max_emission());
  std::vector<CentralMoments4> moments(n);
  std::vector<CentralMoments4> parts;  // per item of a wave: its samples' moments, merged per patch in item order
  PathCounters total;
  // Over MPI each rank traces a block of each wave's tasks (their own streams), then all share the wave's items'
  // sums (a rank's items are those of its tasks: consecutive) and the tasks' counters.
  const auto wave_blocks = [&](std::size_t t0, std::size_t t1) {
    std::vector<distributed::Range> ranges = distributed::all_blocks(t1 - t0), items;
    const std::size_t i0 = t0 * per_task, i1 = std::min(item_count, t1 * per_task);
    for (const distributed::Range& r : ranges)
      items.push_back({std::min(i1 - i0, r.begin * per_task), std::min(i1 - i0, r.end * per_task)});
    return std::pair{ranges, items};
  };
  std::optional<Progress> progress;
  if (options.progress) {
    std::size_t my_items = 0;
    for (std::size_t t0 = 0; t0 < tasks; t0 += wave_tasks)
      my_items += wave_blocks(t0, std::min(tasks, t0 + wave_tasks)).second[static_cast<std::size_t>(distributed::rank())].size();
    progress.emplace("path tracing patches", my_items);
  }
  for (std::size_t t0 = 0; t0 < tasks; t0 += wave_tasks) {
    const std::size_t t1 = std::min(tasks, t0 + wave_tasks);
    const std::size_t i0 = t0 * per_task, i1 = std::min(item_count, t1 * per_task);
    const auto blocks_of_wave = wave_blocks(t0, t1);
    const std::vector<distributed::Range>& ranges = blocks_of_wave.first;
    const std::vector<distributed::Range>& item_ranges = blocks_of_wave.second;
    const distributed::Range mine = ranges[static_cast<std::size_t>(distributed::rank())];
    parts.assign(i1 - i0, CentralMoments4{});
    std::vector<PathCounters> task_counters(t1 - t0);
    parallel_for(
        mine.size(),
        [&](std::size_t local) {
          const std::size_t task = t0 + mine.begin + local;
          const std::size_t first = task * per_task, last = std::min(item_count, first + per_task);
          std::vector<Item> items;
          items.reserve(last - first);
          std::size_t samples_before = 0;
          for (std::size_t k = first; k < last; ++k) {
            Item item;
            item.patch = k / blocks;
            item.s0 = static_cast<long>(k % blocks) * kBlock;
            item.s1 = std::min(options.spp, item.s0 + kBlock);
            item.first = samples_before;
            samples_before += static_cast<std::size_t>(item.s1 - item.s0);
            items.push_back(item);
          }
          trace_items(patches, geometry, integrator, items, options.seed, inverse_scale, parts.data() + (first - i0),
                      task_counters[task - t0]);
          if (progress) progress->advance(last - first);
        },
        1);
    distributed::share_blocks(parts, item_ranges);
    distributed::share_blocks(task_counters, ranges);
    for (std::size_t k = i0; k < i1; ++k) {
      moments[k / blocks].merge(parts[k - i0]);
    }
    for (const PathCounters& c : task_counters) total.add(c);
  }
  if (progress) progress->finish();

  // Unbiased per-sample variance of the scaled samples, scaled back: var = s^2 var(Y / s) is infinite only when
  // the variance itself does not fit a double; B and B_se = s se(Y / s) are finite whenever the samples are.
  Solution sol;
  sol.method = std::string("pathtrace-") + to_string(options.integrator.kind);
  sol.B.resize(static_cast<Eigen::Index>(n), 3);
  sol.B_se.resize(static_cast<Eigen::Index>(n), 3);
  sol.var.resize(static_cast<Eigen::Index>(n), 3);
  sol.vov.resize(static_cast<Eigen::Index>(n), 3);
  const double scale = 1 / inverse_scale;
  const double m = static_cast<double>(options.spp);
  for (std::size_t i = 0; i < n; ++i) {
    const CentralMoments4& x = moments[i];
    const Rgb var = x.M2 / (m - 1);
    const auto r = static_cast<Eigen::Index>(i);
    sol.B.row(r) = (patches.E[i] + x.mean * scale).transpose();
    sol.var.row(r) = (var * scale * scale).transpose();
    sol.B_se.row(r) = ((var / m).sqrt() * scale).transpose();
    sol.vov.row(r) = x.vov().transpose();  // scale-free
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
  sol.info["shadow_rays"] = static_cast<double>(total.shadow_rays);
  sol.info["escapes"] = static_cast<double>(total.escapes);
  sol.info["rays_per_second"] = sol.seconds > 0 ? static_cast<double>(total.rays) / sol.seconds : 0.0;
  sol.info["rr_depth"] = options.integrator.rr_depth;
  sol.info["max_depth"] = options.integrator.max_depth;
  return sol;
}

}  // namespace radwalk
