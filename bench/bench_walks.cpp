// bench_walks: transitions per second of the random-walk kernels on the Cornell box, 1 thread and all threads.
//
// Scene: meshes/cornell_box.obj patched to about 300 patches (bench_scene.h), F from
// estimate_form_factors with 20,000 rays per patch through EmbreeVisibility (so F has the density of a real run).
//   matrix chain   raw kernel: one Markov chain per chunk, roulette + alias draw per step, restarted at a random
//                  patch when it stops (the cost of a transition without any scoring);
//   matrix walks   solve_random_walk gather-collision and shoot-collision (full estimator: streams, weights,
//                  scores, moments); transitions/s = Solution::steps / seconds;
//   ray walks      the same with the ray kernel (each transition traces one ray through EmbreeVisibility);
//   raw Embree     EmbreeVisibility::intersect on pre-generated rays of the same kind (uniform patch point, cosine
//                  direction, spawn_ray), tracing only, for comparison with the ray kernel: one Ray per call
//                  (rtcIntersect1) and one RayPacket of 16 per call (rtcIntersect16; the rays packed in single
//                  precision beforehand, as the ray kernel makes them, so neither pays a conversion).
// Target: matrix kernel >= 20 M transitions/s per core. Each rate is given per wall-clock second and per CPU
// second of the process (CLOCK_PROCESS_CPUTIME_ID) over the same timed region, the per-core figure that stays
// meaningful on a shared machine. Then the ratio of the ray kernel's transitions to the better raw Embree rate
// (single rays or packets), per CPU second, 1 thread and all threads: the target is >= 0.8 (docs/benchmarks.md).
// Then the six estimators side by side on the same scene and F (compare_random_walks: R = 4 runs, 200 walks per
// patch, matrix kernel, exact variances and the dense solve as reference).
// Every rate is the best of R runs (--repeat R, default 3), the ray rows and the raw rows alike.
// Usage: bench_walks [--quick] [--ray-only] [--repeat R] [--scene PATH]   (--ray-only: only the ray rows and the
// ratios)
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "bench_scene.h"
#include "core/parallel.h"
#include "core/rng.h"
#include "core/timer.h"
#include "formfactor/form_factors.h"
#include "solve/problem.h"
#include "visibility/embree_visibility.h"
#include "visibility/ray_packet.h"
#include "walk/matrix_kernel.h"
#include "walk/random_walk_solver.h"
#include "walk/walk_compare.h"

using namespace radwalk;
using radwalk::bench::cpu_seconds;

namespace {

// A rate per wall-clock second and per CPU second of the process, over the same timed region.
struct Rate {
  double wall = 0, cpu = 0;
};

// Runs f(), which returns its work count, and times it.
template <class F>
Rate measure(F&& f) {
  const Timer wall;
  const double c0 = cpu_seconds();
  const double count = f();
  const double w = wall.seconds(), c = cpu_seconds() - c0;
  return {count / w, count / c};
}

// Raw matrix-kernel chain: `steps` transitions in fixed chunks; returns transitions per second.
Rate matrix_chain(const MatrixKernel& kernel, long steps) {
  const std::size_t chunk = 1 << 20;
  const auto n = static_cast<std::size_t>(steps);
  std::vector<std::size_t> sink((n + chunk - 1) / chunk);
  const Rate rate = measure([&] {
    parallel_chunks(n, chunk, [&](std::size_t b, std::size_t e) {
    Rng rng = stream(7, StreamDomain::benchmark, b / chunk);
    WalkCounters counters;
    std::size_t k = 0, visited = 0;
    for (std::size_t s = b; s < e; ++s) {
      PatchIndex j = rng.uniform() < kernel.tables().p[k] ? kernel.sample(k, rng, counters) : kEscaped;
      if (j < 0) j = static_cast<PatchIndex>(rng.uniform_index(static_cast<std::uint32_t>(kernel.size())));
      k = static_cast<std::size_t>(j);
      visited += k;
    }
    sink[b / chunk] = visited;
    });
    return double(steps);
  });
  std::size_t total = 0;
  for (std::size_t v : sink) total += v;
  if (total == 42) std::printf(" ");  // keep the loop alive
  return rate;
}

// Transitions (Solution::steps) per second of the walks of solve_random_walk (Solution::seconds: without the
// variance-radius check a stored F adds); the CPU rate rescales it by wall / CPU time of the whole call.
Rate walks_rate(const RadiosityProblem& problem, const PatchSet& patches, const Visibility& vis,
                const std::string& method, const std::string& kernel, long walks) {
  WalkOptions o;
  o.method = parse_walk_method(method);
  o.kernel = parse_walk_kernel(kernel);
  o.walks_per_patch = o.particles = walks;
  const Timer wall;
  const double c0 = cpu_seconds();
  const Solution s = solve_random_walk(problem, &patches, &vis, o);
  const double w = wall.seconds(), c = cpu_seconds() - c0;
  const double rate = double(s.steps) / s.seconds;
  return {rate, rate * w / c};
}

// Raw Embree: EmbreeVisibility::intersect on pre-generated rays, one Ray per call (rtcIntersect1), or the same rays
// packed beforehand, one RayPacket of 16 per call (rtcIntersect16).
struct RawRays {
  std::vector<Ray> rays;
  std::vector<RayPacket> packets;  // the same rays, 16 per packet
  explicit RawRays(std::vector<Ray> r) : rays(std::move(r)), packets((rays.size() + kPacketSize - 1) / kPacketSize) {
    for (std::size_t k = 0; k < rays.size(); ++k) {
      RayPacket& p = packets[k / kPacketSize];
      p.set(k % kPacketSize, rays[k]);
      p.count = k % kPacketSize + 1;
    }
  }
};

Rate embree_rate(const EmbreeVisibility& vis, const RawRays& raw, bool packet) {
  const std::vector<Ray>& rays = raw.rays;
  const std::vector<RayPacket>& packets = raw.packets;
  const std::size_t count = rays.size();
  std::vector<int> hit(count);
  return measure([&] {
    if (packet)
      parallel_chunks(packets.size(), 4096 / kPacketSize, [&](std::size_t b, std::size_t e) {
        Hit hits[kPacketSize];
        for (std::size_t p = b; p < e; ++p) {
          vis.intersect(packets[p], hits);
          for (std::size_t q = 0; q < packets[p].count; ++q) hit[p * kPacketSize + q] = hits[q].patch;
        }
      });
    else
      parallel_for(count, [&](std::size_t r) { hit[r] = vis.intersect(rays[r]).patch; }, 4096);
    return double(count);
  });
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false, ray_only = false;
  int repeat = 3;
  std::string scene = bench::default_scene();
  for (int a = 1; a < argc; ++a) {
    if (!std::strcmp(argv[a], "--quick")) quick = true;
    else if (!std::strcmp(argv[a], "--ray-only")) ray_only = true;
    else if (!std::strcmp(argv[a], "--scene") && a + 1 < argc) scene = argv[++a];
    else if (!std::strcmp(argv[a], "--repeat") && a + 1 < argc) repeat = std::max(1, std::atoi(argv[++a]));
  }
  const PatchSet patches = bench::patched_to(scene, 300, 0.15);
  const EmbreeVisibility vis(patches);
  FormFactorOptions ffo;
  ffo.rays_per_patch = quick || ray_only ? 2000 : 20000;  // the ray rows do not use F
  const FormFactors ff = estimate_form_factors(patches, vis, ffo);
  const RadiosityProblem problem = make_problem(patches, ff.F);
  const MatrixKernel kernel(problem, survival_probabilities(problem.rho, {}));
  std::printf("scene %s: %zu patches, F has %ld non-zeros (%.1f per row), alias tables %.2f MB\n", scene.c_str(),
              patches.size(), long(ff.F.nonZeros()), double(ff.F.nonZeros()) / double(patches.size()),
              double(kernel.rows().memory_bytes()) / 1e6);
  const int all = active_threads();
  const long chain_steps = quick ? 20'000'000 : 200'000'000;
  const long matrix_walks = quick ? 2000 : 20000;        // per patch (gathering)
  const long ray_walks = quick ? 100 : 1000;             // per patch (gathering)
  const std::size_t embree_rays = quick ? 500'000 : 4'000'000;
  std::printf("%-32s %24s %24s\n", "millions per second", "1 thread: wall / cpu", (std::to_string(all) + " threads: wall / cpu").c_str());
  // One row: f() measured with 1 thread and with all threads.
  struct Rates {
    Rate one, all;
  };
  // Each measured `repeat` times; the fastest (per CPU second) of the runs is kept, the same for every row, so a
  // run slowed by another process on the machine does not decide a ratio.
  auto best_of = [&](auto&& f) {
    Rate best;
    for (int k = 0; k < repeat; ++k) {
      const Rate r = f();
      if (r.cpu > best.cpu) best = r;
    }
    return best;
  };
  auto row = [&](const char* name, auto&& f) {
    Rates r;
    {
      ThreadLimit limit(1);
      r.one = best_of(f);
    }
    r.all = best_of(f);
    std::printf("%-32s %11.2f / %10.2f %11.2f / %10.2f\n", name, r.one.wall / 1e6, r.one.cpu / 1e6,
                r.all.wall / 1e6, r.all.cpu / 1e6);
    return r;
  };
  if (!ray_only) {
    row("matrix chain (raw kernel)", [&] { return matrix_chain(kernel, chain_steps); });
    row("matrix gather-collision",
        [&] { return walks_rate(problem, patches, vis, "gather-collision", "matrix", matrix_walks); });
    row("matrix gather-absorption",
        [&] { return walks_rate(problem, patches, vis, "gather-absorption", "matrix", matrix_walks); });
    row("matrix shoot-collision", [&] {
      return walks_rate(problem, patches, vis, "shoot-collision", "matrix", matrix_walks * long(patches.size()));
    });
  }
  // The ray kernel runs without F, as it would in practice (and without the variance-radius check F enables).
  RadiosityProblem no_F = problem;
  no_F.F = SparseF();
  const Rates ray_gather = row("ray gather-collision", [&] {
    return walks_rate(no_F, patches, vis, "gather-collision", "ray", ray_walks);
  });
  const Rates ray_ev = row("ray gather-expected-value", [&] {
    return walks_rate(no_F, patches, vis, "gather-expected-value", "ray", ray_walks);
  });
  const Rates ray_shoot = row("ray shoot-collision", [&] {
    return walks_rate(no_F, patches, vis, "shoot-collision", "ray", ray_walks * long(patches.size()));
  });
  const RawRays raw_rays(bench::incoherent_rays(patches, embree_rays, 99));  // made once, outside the timing
  const Rates single =
      row("raw Embree rays (intersect1)", [&] { return embree_rate(vis, raw_rays, false); });
  const Rates packet =
      row("raw Embree rays (intersect16)", [&] { return embree_rate(vis, raw_rays, true); });
  // Target: ray-kernel transitions >= 0.8 x the better raw Embree rate, per CPU second.
  const double raw_one = std::max(single.one.cpu, packet.one.cpu);
  const double raw_all = std::max(single.all.cpu, packet.all.cpu);
  std::printf("\n%-56s %10s %11s\n", "ray kernel / best raw Embree, per CPU second (>= 0.8)", "1 thread",
              (std::to_string(all) + " threads").c_str());
  for (const auto& [name, r] : {std::pair{"ray gather-collision", ray_gather},
                                std::pair{"ray gather-expected-value", ray_ev},
                                std::pair{"ray shoot-collision", ray_shoot}})
    std::printf("%-56s %10.2f %11.2f\n", name, r.one.cpu / raw_one, r.all.cpu / raw_all);
  if (ray_only) return 0;

  CompareOptions co;
  co.runs = 4;
  co.walk.walks_per_patch = quick ? 50 : 200;
  const CompareResult cr = compare_random_walks(problem, &patches, &vis, co);
  std::printf("\nestimators on the same budget (%d runs x %ld walks per patch; shooting: the same total)\n%s",
              co.runs, co.walk.walks_per_patch, format_compare_summary(cr.summary).c_str());
  return 0;
}
