#include "pathtrace/camera_response.h"

#include <vector>

#include "core/error.h"
#include "core/parallel.h"

namespace radwalk {

CameraResponse camera_response(const PinholeCamera& camera, const Visibility& visibility, const PatchSet& patches,
                               int points_per_side) {
  if (points_per_side < 1)
    throw InputError("camera response: points per pixel side must be >= 1 (got " + std::to_string(points_per_side) +
                     ")");
  const int W = camera.width(), H = camera.height(), n = points_per_side;
  const auto N = static_cast<Eigen::Index>(patches.size());
  // Per row: the count of points per patch (sparse: (patch, count) pairs in pixel order) and boundary pixels.
  struct Row {
    std::vector<std::pair<PatchIndex, long>> counts;
    long boundary = 0;
  };
  std::vector<Row> rows(static_cast<std::size_t>(H));
  parallel_for(
      static_cast<std::size_t>(H),
      [&](std::size_t y) {
        Row& row = rows[y];
        std::vector<PatchIndex> seen(static_cast<std::size_t>(n * n));
        for (int x = 0; x < W; ++x) {
          for (int a = 0; a < n; ++a)
            for (int b = 0; b < n; ++b) {
              const Ray ray = camera.generate_ray(x + (b + 0.5) / n, static_cast<double>(y) + (a + 0.5) / n);
              const Hit hit = visibility.intersect(ray);
              seen[static_cast<std::size_t>(a * n + b)] = hit.missed() || !hit.front ? -1 : hit.patch;
            }
          bool uniform = true;
          for (const PatchIndex p : seen) uniform = uniform && p == seen[0];
          row.boundary += !uniform;
          for (const PatchIndex p : seen)
            if (p >= 0) row.counts.emplace_back(p, 1);
        }
      },
      1);
  CameraResponse r;
  r.pixels = long(W) * H;
  r.fraction = Eigen::VectorXd::Zero(N);
  Eigen::VectorXd count = Eigen::VectorXd::Zero(N);
  for (const Row& row : rows) {
    r.boundary_pixels += row.boundary;
    for (const auto& [p, c] : row.counts) count(p) += double(c);
  }
  r.fraction = count / (double(r.pixels) * n * n);
  r.R = Eigen::VectorXd::Zero(N);
  for (Eigen::Index i = 0; i < N; ++i)
    if (r.fraction(i) > 0) r.R(i) = r.fraction(i) / (kPi * patches.area[std::size_t(i)]);
  return r;
}

}  // namespace radwalk
