#include "solve/synthetic_problem.h"

#include <algorithm>
#include <map>
#include <vector>

#include "core/error.h"
#include "core/rng.h"

namespace radwalk {

RadiosityProblem make_synthetic_problem(long patches, int rays, std::uint64_t seed) {
  if (patches < 2 || rays < 1)
    throw InputError("synthetic problem needs at least 2 patches and 1 ray per patch");
  const auto n = Eigen::Index(patches);
  const long window = std::max<long>(2, patches / 50);
  RadiosityProblem p;
  p.area = Eigen::VectorXd::Ones(n);
  p.rho.resize(n, 3);
  p.E = PatchRgb::Zero(n, 3);
  const Rgb white(0.725, 0.71, 0.68), red(0.63, 0.065, 0.05), green(0.14, 0.45, 0.091), light(0.78, 0.78, 0.78);
  std::vector<Eigen::Triplet<float, std::int32_t>> t;
  t.reserve(std::size_t(patches) * std::size_t(std::min(rays, 2 * int(window) + 64)));
  for (Eigen::Index i = 0; i < n; ++i) {
    // Material by block: 1/6 red, 1/6 green, the rest white; every 100th patch a light.
    const long block = long(i) * 6 / patches;
    p.rho.row(i) = (block == 1 ? red : block == 2 ? green : white).transpose();
    if (i % 100 == 50 || (patches < 100 && i == 0)) {
      p.rho.row(i) = light.transpose();
      p.E.row(i) = kPi * Rgb(17, 12, 4).transpose();
    }
    // Landing counts of the rays from i.
    Rng rng = stream(seed, StreamDomain::synthetic_problem, std::uint64_t(i));
    std::map<std::int32_t, int> hits;
    for (int r = 0; r < rays; ++r) {
      const double u = rng.uniform();
      if (u < 0.1) continue;
      long j;
      if (u < 0.55) {
        j = long(i) + long(rng.uniform_index(std::uint32_t(2 * window + 1))) - window;
        j = ((j % patches) + patches) % patches;
      } else {
        j = long(rng.uniform_index(std::uint32_t(patches)));
      }
      if (j == long(i)) j = (j + 1) % patches;
      ++hits[std::int32_t(j)];
    }
    for (const auto& [j, count] : hits) t.emplace_back(std::int32_t(i), j, float(count) / float(rays));
  }
  p.F.resize(n, n);
  p.F.setFromTriplets(t.begin(), t.end());
  p.F.makeCompressed();
  return p;
}

}  // namespace radwalk
