#include "hierarchy/leaf_variation.h"

#include <array>

#include "core/check.h"
#include "core/parallel.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "formfactor/point_polygon_form_factor.h"
#include "hierarchy/direct_refinement.h"
#include "visibility/ray_offset.h"

namespace radwalk {

LeafVariation leaf_variation(const PatchSet& roots, const Visibility& visibility, const ElementTree& tree,
                             const std::vector<ElementIndex>& leaves, const PatchRgb& B, int points_side,
                             int directions, std::uint64_t seed) {
  RADWALK_CHECK(points_side >= 2 && directions >= 1);
  RADWALK_CHECK(B.rows() == static_cast<Eigen::Index>(leaves.size()));
  const int m = points_side, M = m * m, L = directions;
  const std::vector<std::size_t> emitters = emitter_roots(roots);
  const double eps = ray_epsilon(roots);
  std::vector<Eigen::Index> row(tree.size(), -1);
  for (std::size_t k = 0; k < leaves.size(); ++k) row[static_cast<std::size_t>(leaves[k])] = static_cast<Eigen::Index>(k);
  // The reflected part of B_h at a point of input patch h: the leaf containing it.
  const auto reflected_at = [&](std::size_t h, const Vec3& p) {
    std::size_t e = h;
    while (!tree.is_leaf(e)) e = static_cast<std::size_t>(tree.child_containing(e, p, roots.normal[h]));
    const Eigen::Index k = row[e];
    if (k < 0) return Rgb(Rgb::Zero());  // a leaf not in the list (not solved): no contribution
    return Rgb(B.row(k).transpose() - roots.E[h]);
  };

  LeafVariation out;
  out.W2 = PatchRgb::Zero(static_cast<Eigen::Index>(leaves.size()), 3);
  std::vector<long> rays(leaves.size(), 0);
  parallel_for(
      leaves.size(),
      [&](std::size_t k) {
        const auto e = static_cast<std::size_t>(leaves[k]);
        const auto r = static_cast<std::size_t>(tree.root[e]);
        const Rgb& rho = roots.rho[r];
        if (!(rho > 0).any()) return;
        const Vec3& n = roots.normal[r];
        const Frame frame(n);
        const PatchRayOffset offset = patch_ray_offset(roots, r, eps);
        Rng prng = stream(seed, StreamDomain::hierarchical_variation, e, 0);
        std::vector<Vec3> y(static_cast<std::size_t>(M));
        for (int s = 0; s < M; ++s) {
          const double u1 = ((s % m) + prng.uniform()) / m, u2 = ((s / m) + prng.uniform()) / m;
          y[static_cast<std::size_t>(s)] = element_point(tree, e, u1, u2);
        }
        std::array<std::vector<Rgb>, 2> g;
        for (int q = 0; q < 2; ++q) {
          Rng rng = stream(seed, StreamDomain::hierarchical_variation, e, 1 + static_cast<std::uint64_t>(q));
          std::vector<Vec3> w(static_cast<std::size_t>(L));
          for (auto& v : w) {
            const double u1 = rng.uniform(), u2 = rng.uniform();
            v = frame.to_world(sample_cosine_hemisphere(u1, u2));
          }
          std::vector<Vec3> z(emitters.size());
          for (std::size_t a = 0; a < emitters.size(); ++a) {
            const double u1 = rng.uniform(), u2 = rng.uniform();
            z[a] = sample_patch_point(roots, emitters[a], u1, u2);
          }
          auto& gq = g[static_cast<std::size_t>(q)];
          gq.assign(static_cast<std::size_t>(M), Rgb::Zero());
          for (int s = 0; s < M; ++s) {
            const Vec3& x = y[static_cast<std::size_t>(s)];
            Rgb f = Rgb::Zero();
            for (std::size_t a = 0; a < emitters.size(); ++a) {
              const std::size_t em = emitters[a];
              if (em == r) continue;
              Vec3 c[4];
              const int count = roots.corner_count(em);
              for (int b = 0; b < count; ++b) c[b] = roots.corner(em, b);
              const double F = point_polygon_form_factor(x, n, c, count, roots.normal[em]);
              if (!(F > 0)) continue;
              f += roots.E[em] * visible_point_form_factor(roots, visibility, offset, x, n, em, z[a], F, eps, rays[k]);
            }
            Rgb reflected = Rgb::Zero();
            for (const Vec3& v : w) {
              const Ray ray = spawn_ray(offset, x, v);
              const Hit hit = visibility.intersect(ray);
              ++rays[k];
              if (hit.missed() || !hit.front) continue;
              const auto h = static_cast<std::size_t>(hit.patch);
              reflected += reflected_at(h, ray.origin + hit.t * ray.direction);
            }
            gq[static_cast<std::size_t>(s)] = f + reflected / L;
          }
        }
        Rgb mean0 = Rgb::Zero(), mean1 = Rgb::Zero();
        for (int s = 0; s < M; ++s) {
          mean0 += g[0][static_cast<std::size_t>(s)];
          mean1 += g[1][static_cast<std::size_t>(s)];
        }
        mean0 /= M;
        mean1 /= M;
        Rgb cov = Rgb::Zero();
        for (int s = 0; s < M; ++s)
          cov += (g[0][static_cast<std::size_t>(s)] - mean0) * (g[1][static_cast<std::size_t>(s)] - mean1);
        out.W2.row(static_cast<Eigen::Index>(k)) = (rho * rho * cov / (M - 1)).transpose();
      },
      16);
  for (const long x : rays) out.rays += x;
  return out;
}

}  // namespace radwalk
