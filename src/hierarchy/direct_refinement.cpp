#include "hierarchy/direct_refinement.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"
#include "core/parallel.h"
#include "core/rng.h"
#include "formfactor/point_polygon_form_factor.h"
#include "visibility/ray_offset.h"

namespace radwalk {

std::vector<std::size_t> emitter_roots(const PatchSet& roots) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < roots.size(); ++i)
    if ((roots.E[i] > 0).any()) out.push_back(i);
  return out;
}

namespace {

struct ElementDirect {
  Rgb D = Rgb::Zero(), variance = Rgb::Zero();
  double indicator = 0;
  long rays = 0;
};

}  // namespace

double visible_point_form_factor(const PatchSet& roots, const Visibility& visibility, const PatchRayOffset& offset,
                                 const Vec3& x, const Vec3& n, std::size_t k, const Vec3& y, double F, double eps,
                                 long& rays) {
  const Vec3 d = y - x;
  const double r2 = d.squaredNorm();
  if (!(r2 > 0)) return F;
  const double dist = std::sqrt(r2);
  const Vec3 w = d / dist;
  const double cos_x = w.dot(n), cos_y = -w.dot(roots.normal[k]);
  if (!(cos_x > 0 && cos_y > 0)) return F;  // y outside x's hemisphere or behind k's front: G = 0 there
  // The shadow ray as a segment that stops before k's plane, measured from the moved origin (ray_offset.h): the
  // offset pulls the origin towards the receiver's centroid by up to eps r_i / d_i, which on a narrow patch (a
  // stool's 2 cm side, r_i / d_i ~ 23) brought it nearer to y than the tolerance of a test against |y - x|, so the
  // emitter itself was taken for an occluder (those sides' direct light read 21 % to 27 % low).
  const Ray shadow = stop_before_plane(spawn_ray(offset, x, w), dist, y, roots.normal[k], 4 * eps);
  ++rays;
  if (!(shadow.tmax > 0) || !visibility.occluded(shadow)) return F;
  return F - roots.area[k] * cos_x * cos_y / (kPi * r2);
}

namespace {

// The M points of element e (the top of direct_refinement.h).
ElementDirect estimate_element(const PatchSet& roots, const Visibility& visibility, const ElementTree& tree,
                               std::size_t e, const std::vector<std::size_t>& emitters, double eps, int m,
                               std::uint64_t seed) {
  ElementDirect out;
  const auto r = static_cast<std::size_t>(tree.root[e]);
  const Rgb& rho = roots.rho[r];
  if (!(rho > 0).any() || emitters.empty()) return out;
  const Vec3& n = roots.normal[r];
  const PatchRayOffset offset = patch_ray_offset(roots, r, eps);
  Rng rng = stream(seed, StreamDomain::hierarchical_direct, e, 0);
  const int M = m * m;
  // The oracle's points of the emitters, one per emitter shared by the element's M points (common random numbers).
  std::vector<Vec3> shared(emitters.size());
  for (std::size_t a = 0; a < emitters.size(); ++a) {
    const double v1 = rng.uniform(), v2 = rng.uniform();
    shared[a] = sample_patch_point(roots, emitters[a], v1, v2);
  }
  Rgb sum = Rgb::Zero(), sum2 = Rgb::Zero(), hsum = Rgb::Zero(), hsum2 = Rgb::Zero();
  for (int s = 0; s < M; ++s) {
    const double u1 = ((s % m) + rng.uniform()) / m, u2 = ((s / m) + rng.uniform()) / m;
    const Vec3 x = element_point(tree, e, u1, u2);
    Rgb f = Rgb::Zero(), h = Rgb::Zero();
    for (std::size_t a = 0; a < emitters.size(); ++a) {
      const std::size_t k = emitters[a];
      if (k == r) continue;
      const int count = roots.corner_count(k);
      Vec3 c[4];
      for (int b = 0; b < count; ++b) c[b] = roots.corner(k, b);
      const double F = point_polygon_form_factor(x, n, c, count, roots.normal[k]);
      const double v1 = rng.uniform(), v2 = rng.uniform();
      if (!(F > 0)) continue;
      const Vec3 y = sample_patch_point(roots, k, v1, v2);
      f += roots.E[k] * visible_point_form_factor(roots, visibility, offset, x, n, k, y, F, eps, out.rays);
      h += roots.E[k] * visible_point_form_factor(roots, visibility, offset, x, n, k, shared[a], F, eps, out.rays);
    }
    sum += f;
    sum2 += f * f;
    hsum += h;
    hsum2 += h * h;
  }
  const double Md = M;
  const auto sample_variance = [&](const Rgb& s1, const Rgb& s2) {
    const Rgb mean = s1 / Md;
    return M > 1 ? Rgb(((s2 - Md * mean * mean) / (Md - 1)).max(0.0)) : Rgb(Rgb::Zero());
  };
  out.D = rho * sum / Md;
  out.variance = rho * rho * sample_variance(sum, sum2) / Md;
  out.indicator = tree.area[e] * (rho * sample_variance(hsum, hsum2).sqrt()).maxCoeff();
  return out;
}

}  // namespace

DirectRefinement refine_direct_light(const PatchSet& roots, const Visibility& visibility, ElementTree& tree,
                                     const DirectRefinementOptions& options) {
  RADWALK_CHECK(options.points_side >= 1);
  const std::vector<std::size_t> emitters = emitter_roots(roots);
  const double eps = ray_epsilon(roots);
  DirectRefinement result;
  std::vector<ElementIndex> level = tree.leaves();
  std::vector<ElementDirect> values;
  auto grow = [&] {
    result.D.resize(tree.size(), Rgb::Zero());
    result.variance.resize(tree.size(), Rgb::Zero());
    result.indicator.resize(tree.size(), 0.0);
  };
  grow();
  while (!level.empty()) {
    values.assign(level.size(), ElementDirect{});
    parallel_for(
        level.size(),
        [&](std::size_t q) {
          values[q] = estimate_element(roots, visibility, tree, static_cast<std::size_t>(level[q]), emitters, eps,
                                       options.points_side, options.seed);
        },
        16);
    std::vector<ElementIndex> next;
    for (std::size_t q = 0; q < level.size(); ++q) {
      const auto e = static_cast<std::size_t>(level[q]);
      result.D[e] = values[q].D;
      result.variance[e] = values[q].variance;
      result.indicator[e] = values[q].indicator;
      result.shadow_rays += values[q].rays;
      if (values[q].indicator > options.epsilon && tree.level[e] < options.max_level &&
          tree.area[e] / 4 >= options.min_area) {
        const ElementIndex c = tree.split(e);
        ++result.splits;
        for (int k = 0; k < 4; ++k) next.push_back(c + k);
      }
    }
    grow();
    level = std::move(next);
  }
  return result;
}

}  // namespace radwalk
