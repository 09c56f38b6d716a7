#pragma once
// The benchmark programs' scene: the bundled Cornell box, found next to the bench sources (so a benchmark runs
// from any directory), patched to about a target number of patches.
#include <time.h>

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <string>

#include <vector>

#include "core/parallel.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "mesh/read_scene.h"
#include "patch/patching.h"
#include "visibility/ray_offset.h"

namespace radwalk::bench {

// CPU seconds of the whole process (all threads), for rays per CPU second.
inline double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// meshes/cornell_box.obj of this source tree.
inline std::string default_scene() {
  return (std::filesystem::path(__FILE__).parent_path().parent_path() / "meshes/cornell_box.obj").string();
}

// The scene at `path` patched to about `target` patches: max_edge h from the area (h^2 ~ area / target), then
// rescaled by sqrt(count / target) until the count is within `tolerance` of the target (at most 6 tries).
inline PatchSet patched_to(const std::string& path, std::size_t target, double tolerance) {
  const Mesh mesh = load_scene(path);
  PatchSet ps = make_patches(mesh, 0);
  double h = std::sqrt(ps.total_area() / double(target));
  for (int it = 0; it < 6; ++it) {
    ps = make_patches(mesh, h);
    const double ratio = double(ps.size()) / double(target);
    if (std::abs(ratio - 1) < tolerance) break;
    h *= std::sqrt(ratio);
  }
  return ps;
}

// n incoherent rays as form factors and ray-kernel walks shoot them: a random patch, a uniform point on it, a
// cosine-weighted direction about its normal, spawn_ray's offset. Ray k uses the stream (seed, benchmark, k): the same rays for any
// thread count.
inline std::vector<Ray> incoherent_rays(const PatchSet& ps, std::size_t n, std::uint64_t seed) {
  std::vector<Ray> rays(n);
  const double eps = ray_epsilon(ps);
  parallel_for(n, [&](std::size_t k) {
    Rng rng = stream(seed, StreamDomain::benchmark, k);
    const std::size_t i = rng.uniform_index(std::uint32_t(ps.size()));
    const double s1 = rng.uniform(), s2 = rng.uniform();  // each draw its own declarator: sequenced on any compiler
    const Vec3 p = sample_patch_point(ps, i, s1, s2);
    const double d1 = rng.uniform(), d2 = rng.uniform();
    const Vec3 w = Frame(ps.normal[i]).to_world(sample_cosine_hemisphere(d1, d2));
    rays[k] = spawn_ray(ps, i, p, w, eps);
  });
  return rays;
}

}  // namespace radwalk::bench
