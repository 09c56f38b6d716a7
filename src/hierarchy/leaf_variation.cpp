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

namespace {

// What the one-gather model of the header needs at the points of leaves: the scene, the emitters and where each
// input patch's reflected B_h is read.
struct GatherModel {
  const PatchSet& roots;
  const Visibility& visibility;
  const ElementTree& tree;
  const PatchRgb& B;
  std::vector<std::size_t> emitters;
  double eps;
  std::vector<Eigen::Index> row;  // element -> row of B (-1: not a listed leaf)

  GatherModel(const PatchSet& r, const Visibility& v, const ElementTree& t, const std::vector<ElementIndex>& leaves,
              const PatchRgb& b)
      : roots(r), visibility(v), tree(t), B(b), emitters(emitter_roots(r)), eps(ray_epsilon(r)), row(t.size(), -1) {
    for (std::size_t k = 0; k < leaves.size(); ++k)
      row[static_cast<std::size_t>(leaves[k])] = static_cast<Eigen::Index>(k);
  }

  // The reflected part of B_h at a point of input patch h: the leaf containing it.
  Rgb reflected_at(std::size_t h, const Vec3& p) const {
    std::size_t e = h;
    while (!tree.is_leaf(e)) e = static_cast<std::size_t>(tree.child_containing(e, p, roots.normal[h]));
    const Eigen::Index k = row[e];
    if (k < 0) return Rgb::Zero();  // a leaf not in the list (not solved): no contribution
    return B.row(k).transpose() - roots.E[h];
  }

  // The two replicates g_q(y_s) (q = 0, 1) at the points y of element e (the header's g; replicate q's directions
  // and emitter points from stream (seed, hierarchical_variation, e, 1 + q), shared by the points).
  std::array<std::vector<Rgb>, 2> replicates(std::size_t e, const std::vector<Vec3>& y, int L, std::uint64_t seed,
                                             long& rays) const {
    const auto r = static_cast<std::size_t>(tree.root[e]);
    const Vec3& n = roots.normal[r];
    const Frame frame(n);
    const PatchRayOffset offset = patch_ray_offset(roots, r, eps);
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
      gq.assign(y.size(), Rgb::Zero());
      for (std::size_t s = 0; s < y.size(); ++s) {
        const Vec3& x = y[s];
        Rgb f = Rgb::Zero();
        for (std::size_t a = 0; a < emitters.size(); ++a) {
          const std::size_t em = emitters[a];
          if (em == r) continue;
          Vec3 c[4];
          const int count = roots.corner_count(em);
          for (int b = 0; b < count; ++b) c[b] = roots.corner(em, b);
          const double F = point_polygon_form_factor(x, n, c, count, roots.normal[em]);
          if (!(F > 0)) continue;
          f += roots.E[em] * visible_point_form_factor(roots, visibility, offset, x, n, em, z[a], F, eps, rays);
        }
        Rgb reflected = Rgb::Zero();
        for (const Vec3& v : w) {
          const Ray ray = spawn_ray(offset, x, v);
          const Hit hit = visibility.intersect(ray);
          ++rays;
          if (hit.missed() || !hit.front) continue;
          const auto h = static_cast<std::size_t>(hit.patch);
          reflected += reflected_at(h, ray.origin + hit.t * ray.direction);
        }
        gq[s] = f + reflected / L;
      }
    }
    return g;
  }
};

// sum_i (x0_i - mean x0)(x1_i - mean x1) / (n - 1), per channel: the cross-replicate covariance.
Rgb cross_covariance(const std::vector<Rgb>& x0, const std::vector<Rgb>& x1) {
  const auto n = static_cast<double>(x0.size());
  Rgb mean0 = Rgb::Zero(), mean1 = Rgb::Zero();
  for (std::size_t s = 0; s < x0.size(); ++s) {
    mean0 += x0[s];
    mean1 += x1[s];
  }
  mean0 /= n;
  mean1 /= n;
  Rgb cov = Rgb::Zero();
  for (std::size_t s = 0; s < x0.size(); ++s) cov += (x0[s] - mean0) * (x1[s] - mean1);
  return cov / (n - 1);
}

}  // namespace

LeafVariation leaf_variation(const PatchSet& roots, const Visibility& visibility, const ElementTree& tree,
                             const std::vector<ElementIndex>& leaves, const PatchRgb& B, int points_side,
                             int directions, std::uint64_t seed) {
  RADWALK_CHECK(points_side >= 2 && directions >= 1);
  RADWALK_CHECK(B.rows() == static_cast<Eigen::Index>(leaves.size()));
  const int m = points_side, M = m * m, L = directions;
  const GatherModel model(roots, visibility, tree, leaves, B);
  LeafVariation out;
  out.W2 = PatchRgb::Zero(static_cast<Eigen::Index>(leaves.size()), 3);
  std::vector<long> rays(leaves.size(), 0);
  parallel_for(
      leaves.size(),
      [&](std::size_t k) {
        const auto e = static_cast<std::size_t>(leaves[k]);
        const Rgb& rho = roots.rho[static_cast<std::size_t>(tree.root[e])];
        if (!(rho > 0).any()) return;
        Rng prng = stream(seed, StreamDomain::hierarchical_variation, e, 0);
        std::vector<Vec3> y(static_cast<std::size_t>(M));
        for (int s = 0; s < M; ++s) {
          const double u1 = ((s % m) + prng.uniform()) / m, u2 = ((s / m) + prng.uniform()) / m;
          y[static_cast<std::size_t>(s)] = element_point(tree, e, u1, u2);
        }
        const auto g = model.replicates(e, y, L, seed, rays[k]);
        out.W2.row(static_cast<Eigen::Index>(k)) = (rho * rho * cross_covariance(g[0], g[1])).transpose();
      },
      16);
  for (const long x : rays) out.rays += x;
  return out;
}

Vec3 element_bilinear_point(const ElementTree& tree, std::size_t e, double u, double v) {
  RADWALK_CHECK(tree.corner_count[e] == 4);
  const auto& c = tree.corner[e];
  return (1 - v) * ((1 - u) * c[0] + u * c[1]) + v * ((1 - u) * c[3] + u * c[2]);
}

DirectionalVariation leaf_directional_variation(const PatchSet& roots, const Visibility& visibility,
                                                const ElementTree& tree, const std::vector<ElementIndex>& leaves,
                                                const PatchRgb& B, const std::vector<ElementIndex>& elements,
                                                int points_side, int directions, std::uint64_t seed) {
  RADWALK_CHECK(points_side >= 2 && directions >= 1);
  RADWALK_CHECK(B.rows() == static_cast<Eigen::Index>(leaves.size()));
  const int m = points_side, L = directions;
  const GatherModel model(roots, visibility, tree, leaves, B);
  DirectionalVariation out;
  out.along_01.assign(elements.size(), 0.0);
  out.along_03.assign(elements.size(), 0.0);
  std::vector<long> rays(elements.size(), 0);
  parallel_for(
      elements.size(),
      [&](std::size_t k) {
        const auto e = static_cast<std::size_t>(elements[k]);
        RADWALK_CHECK(tree.is_leaf(e));
        const Rgb& rho = roots.rho[static_cast<std::size_t>(tree.root[e])];
        if (tree.corner_count[e] != 4 || !(rho > 0).any()) return;
        // Point (i, j) of the m x m grid: u = (i + jitter) / m along c0 -> c1, v = (j + jitter) / m along c0 -> c3.
        Rng prng = stream(seed, StreamDomain::hierarchical_variation, e, 0);
        std::vector<Vec3> y(static_cast<std::size_t>(m * m));
        for (int j = 0; j < m; ++j)
          for (int i = 0; i < m; ++i) {
            const double u = (i + prng.uniform()) / m, v = (j + prng.uniform()) / m;
            y[static_cast<std::size_t>(j * m + i)] = element_bilinear_point(tree, e, u, v);
          }
        const auto g = model.replicates(e, y, L, seed, rays[k]);
        // The column means (over v, per i) vary along c0 -> c1; the row means (over u, per j) along c0 -> c3.
        std::array<std::vector<Rgb>, 2> column, row;
        for (int q = 0; q < 2; ++q) {
          column[static_cast<std::size_t>(q)].assign(static_cast<std::size_t>(m), Rgb::Zero());
          row[static_cast<std::size_t>(q)].assign(static_cast<std::size_t>(m), Rgb::Zero());
          for (int j = 0; j < m; ++j)
            for (int i = 0; i < m; ++i) {
              const Rgb& x = g[static_cast<std::size_t>(q)][static_cast<std::size_t>(j * m + i)];
              column[static_cast<std::size_t>(q)][static_cast<std::size_t>(i)] += x / m;
              row[static_cast<std::size_t>(q)][static_cast<std::size_t>(j)] += x / m;
            }
        }
        const Rgb r2 = rho * rho;
        out.along_01[k] = (r2 * cross_covariance(column[0], column[1])).sum();
        out.along_03[k] = (r2 * cross_covariance(row[0], row[1])).sum();
      },
      8);
  for (const long x : rays) out.rays += x;
  return out;
}

}  // namespace radwalk
