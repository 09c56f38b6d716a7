#pragma once
// The benchmark programs' scene: the bundled Cornell box, found next to the bench sources (so a benchmark runs
// from any directory), patched to about a target number of patches.
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <string>

#include "mesh/read_scene.h"
#include "patch/patching.h"

namespace radwalk::bench {

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

}  // namespace radwalk::bench
