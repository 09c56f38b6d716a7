#include "formfactor/visible_form_factor.h"

#include <algorithm>
#include <cmath>

#include "formfactor/point_polygon_form_factor.h"
#include "patch/patch_point_sampler.h"
#include "visibility/ray_offset.h"

namespace radwalk {

VisibleFormFactor::VisibleFormFactor(const PatchSet& patches, const Visibility& visibility)
    : patches_(patches), visibility_(visibility), eps_(ray_epsilon(patches)) {}

VisibleFormFactor::Estimate VisibleFormFactor::estimate_with_spread(std::size_t i, std::size_t e, long M,
                                                                  const SobolShift& shift, long& rays) const {
  const PatchPointSampler on_i(patches_, i), on_e(patches_, e);
  const PatchRayOffset offset = patch_ray_offset(patches_, i, eps_);
  const Vec3& ni = patches_.normal[i];
  const Vec3& ne = patches_.normal[e];
  const int count = patches_.corner_count(e);
  Vec3 corner[4];
  for (int k = 0; k < count; ++k) corner[k] = patches_.corner(e, k);
  const double Ae = patches_.area[e];
  constexpr std::size_t kBatch = 64;
  Ray batch[kBatch];
  double weight[kBatch];  // A_e G of each traced ray
  double point_factor[kBatch];  // F(x -> e) of each traced ray's sample
  bool blocked[kBatch];
  std::size_t pending = 0;
  double sum = 0, sum_squares = 0;  // of the scores f_s (the sum in the order of the mean's former formula)
  auto trace = [&] {
    visibility_.occluded(batch, blocked, pending);
    for (std::size_t q = 0; q < pending; ++q) {
      if (blocked[q]) sum -= weight[q];
      const double f = point_factor[q] - (blocked[q] ? weight[q] : 0.0);
      sum_squares += f * f;
    }
    rays += static_cast<long>(pending);
    pending = 0;
  };
  for (long s = 0; s < M; ++s) {
    const auto u = sobol_point(static_cast<std::uint32_t>(s), shift);
    const Vec3 x = on_i.point(u[0], u[1]);
    const double Fx = point_polygon_form_factor(x, ni, corner, count, ne);
    if (!(Fx > 0)) continue;  // e entirely behind x's plane or x behind e's: G = 0 on all of e
    sum += Fx;
    const Vec3 y = on_e.point(u[2], u[3]);
    const Vec3 d = y - x;
    const double r2 = d.squaredNorm();
    const double r = std::sqrt(r2);
    const Vec3 w = d / r;
    const double cos_x = ni.dot(w), cos_y = -ne.dot(w);
    // Stop short of e's plane as the offset origin sees it (at grazing angles the offset moves that plane nearer
    // than r - 4 eps).
    const Ray ray = r2 > 0 && cos_x > 0 && cos_y > 0 ? stop_before_plane(spawn_ray(offset, x, w), r, corner[0], ne, 4 * eps_)
                                                     : Ray{};
    if (!(r2 > 0 && cos_x > 0 && cos_y > 0 && ray.tmax > 0)) {
      sum_squares += Fx * Fx;  // no shadow ray: f_s = F(x -> e)
      continue;
    }
    batch[pending] = ray;
    weight[pending] = Ae * cos_x * cos_y / (kPi * r2);
    point_factor[pending] = Fx;
    if (++pending == kBatch) trace();
  }
  if (pending) trace();
  Estimate out;
  const double m = static_cast<double>(M);
  out.mean = sum / m;
  if (M > 1) out.variance_of_mean = std::max(0.0, (sum_squares - m * out.mean * out.mean) / (m - 1)) / m;
  return out;
}

}  // namespace radwalk
