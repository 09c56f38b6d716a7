#include "hierarchy/hierarchical_jacobi.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/check.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/sampling.h"
#include "core/timer.h"
#include "hierarchy/cluster_tree.h"
#include "hierarchy/direct_refinement.h"
#include "hierarchy/push_pull.h"
#include "visibility/ray_offset.h"
#include "walk/replicates.h"
#include "walk/stratified_emission.h"

namespace radwalk {
namespace {

constexpr double kStopFraction = 1e-6;
constexpr int kMaxIterations = 200;
constexpr long kMinRays = 16;

// A ray's end point and what it carries, recorded by the parallel trace for the ordered descent.
struct Deposit {
  Vec3 point;
  Rgb power;             // rho_h W_l / n_k (per channel)
  Rgb incident;          // W_l / n_k: the power a cluster receives (its members reflect it by their own rho)
  double cap;            // max_c rho_hc P_l: T_e's value when the form factor estimate reaches 1
  std::int32_t patch;    // the patch hit
  ElementIndex shooter;  // the leaf the ray left
};

// The oracle's transfer T_e from shooter leaf l to element e of patch h (hierarchical_jacobi.h): from the elements'
// centres c, not from the ray's own end points, so every ray of one shooter landing in e takes the same decision at
// e (a decision that depended on where in e the ray landed would move power between e's children: biased).
double transfer(const ElementTree& tree, const std::vector<Vec3>& centre, std::size_t l, std::size_t e,
                const Vec3& n_l, const Vec3& n_h, double cap) {
  const Vec3 v = centre[e] - centre[l];
  const double d2 = v.squaredNorm();
  if (!(d2 > 0)) return cap;
  const double d = std::sqrt(d2);
  const double cos_x = std::max(0.0, v.dot(n_l) / d), cos_y = std::max(0.0, -v.dot(n_h) / d);
  const double F = std::min(1.0, tree.area[e] * cos_x * cos_y / (kPi * d2));
  return cap * F * std::min(1.0, std::sqrt(tree.area[e]) / d);
}

Vec3 centre_of(const ElementTree& tree, std::size_t e) {
  Vec3 c = Vec3::Zero();
  for (int k = 0; k < tree.corner_count[e]; ++k) c += tree.corner[e][static_cast<std::size_t>(k)];
  return c / tree.corner_count[e];
}

void check_options(const HierarchicalOptions& o) {
  if (!(o.tol > 0) || !std::isfinite(o.tol))
    throw InputError("--hierarchical: the tolerance must be a finite number > 0 (got " + std::to_string(o.tol) + ")");
  if (o.replicates < 2) throw InputError("--hierarchical: --replicates must be at least 2 (the error bars need them)");
  if (o.particles < 1) throw InputError("--hierarchical: --particles must be at least 1");
  if (o.max_level < 0 || o.max_level > 30) throw InputError("--hierarchical-levels must be in [0, 30]");
  if (o.points_side < 1 || o.points_side > 64) throw InputError("--hierarchical-points must be in [1, 4096] (a square)");
  if (!(o.min_area >= 0) || !std::isfinite(o.min_area))
    throw InputError("--hierarchical-min-area must be a finite number >= 0");
  if (o.clusters && (!(o.cluster_ratio > 0) || !std::isfinite(o.cluster_ratio)))
    throw InputError("--hierarchical-cluster-ratio must be a finite number > 0");
  if (o.clusters && o.cluster_leaf_size < 2) throw InputError("--hierarchical: a leaf cluster needs at least 2 patches");
}

}  // namespace

bool within_depth(const ElementTree& tree, std::size_t e, const HierarchicalOptions& options) {
  return tree.level[e] < options.max_level && tree.area[e] / 4 >= options.min_area;
}

bool splittable(const ElementTree& tree, std::size_t e, const HierarchicalOptions& options) {
  return tree.is_leaf(e) && within_depth(tree, e, options);
}

HierarchicalResult solve_hierarchical(const PatchSet& roots, const Visibility& visibility,
                                      const HierarchicalOptions& options) {
  return solve_hierarchical(roots, visibility, make_element_tree(roots), options);
}

HierarchicalResult solve_hierarchical(const PatchSet& roots, const Visibility& visibility, ElementTree start,
                                      const HierarchicalOptions& options) {
  check_options(options);
  RADWALK_CHECK(start.size() >= roots.size());
  const Timer timer;
  HierarchicalResult result;
  ElementTree& tree = result.tree;
  tree = std::move(start);
  const std::size_t N = roots.size();
  Rgb emitted = Rgb::Zero();
  double rho_bar = 0, total_area = 0;
  for (std::size_t i = 0; i < N; ++i) {
    emitted += roots.area[i] * roots.E[i];
    rho_bar += roots.area[i] * roots.rho[i].mean();
    total_area += roots.area[i];
  }
  rho_bar = total_area > 0 ? std::clamp(rho_bar / total_area, 0.0, 0.99) : 0.0;
  result.epsilon = options.tol * emitted.maxCoeff();

  // 1. The direct light and its refinement.
  DirectRefinementOptions d;
  d.epsilon = options.direct_oracle ? result.epsilon : std::numeric_limits<double>::infinity();
  d.min_area = options.min_area;
  d.max_level = options.max_level;
  d.points_side = options.points_side;
  d.seed = options.direct_seed != 0 ? options.direct_seed : options.seed;
  DirectRefinement direct = refine_direct_light(roots, visibility, tree, d);
  result.shadow_rays = direct.shadow_rays;
  result.direct_splits = direct.splits;
  std::vector<Rgb>& D = direct.D;
  std::vector<Rgb>& Dvar = direct.variance;

  const int R = options.replicates;
  std::vector<std::vector<Rgb>> Bs(static_cast<std::size_t>(R));
  const double eps = ray_epsilon(roots);
  std::vector<PatchRayOffset> offset(N);
  for (std::size_t i = 0; i < N; ++i) offset[i] = patch_ray_offset(roots, i, eps);
  std::vector<double> rho_max(N);
  for (std::size_t i = 0; i < N; ++i) rho_max[i] = roots.rho[i].maxCoeff();
  const ClusterTree clusters = options.clusters ? make_cluster_tree(roots, options.cluster_leaf_size) : ClusterTree();
  result.clusters = clusters.size();
  std::vector<std::int32_t> chain;  // a patch's clusters, leaf cluster first

  // Splits leaf e during replicate r: the children take e's B in replicates 0 .. r and its D.
  const auto split = [&](std::size_t e, int r, std::vector<Rgb>& gathered) {
    const ElementIndex c = tree.split(e);
    ++result.transport_splits;
    for (int q = 0; q <= r; ++q)
      for (int k = 0; k < 4; ++k) Bs[static_cast<std::size_t>(q)].push_back(Bs[static_cast<std::size_t>(q)][e]);
    for (int k = 0; k < 4; ++k) {
      D.push_back(D[e]);
      Dvar.push_back(Dvar[e]);
      gathered.push_back(Rgb::Zero());
    }
    return c;
  };

  for (int r = 0; r < R; ++r) {
    std::vector<Rgb>& B = Bs[static_cast<std::size_t>(r)];
    B.assign(tree.size(), Rgb::Zero());
    std::vector<ElementIndex> leaves = tree.leaves();
    for (const ElementIndex l : leaves) {
      const auto e = static_cast<std::size_t>(l);
      B[e] = roots.E[static_cast<std::size_t>(tree.root[e])] + D[e];
    }
    std::vector<Rgb> S(tree.size(), Rgb::Zero());  // the unshot radiosity at the leaves
    for (const ElementIndex l : leaves) S[static_cast<std::size_t>(l)] = D[static_cast<std::size_t>(l)];
    const auto unshot = [&](const std::vector<ElementIndex>& ls) {
      double phi = 0;
      for (const ElementIndex l : ls) phi += tree.area[static_cast<std::size_t>(l)] * S[static_cast<std::size_t>(l)].abs().sum();
      return phi;
    };
    const double phi0 = unshot(leaves);
    if (!(phi0 > 0)) continue;
    const long share = options.particles / R + (r < options.particles % R ? 1 : 0);
    const double rays_per_power = static_cast<double>(std::max<long>(share, 1)) * (1 - rho_bar) / phi0;
    for (int k = 0; k < kMaxIterations; ++k) {
      leaves = tree.leaves();
      const double phi = unshot(leaves);
      if (!(phi > kStopFraction * phi0)) break;
      const long n = std::max(kMinRays, std::lround(rays_per_power * phi));
      const auto L = static_cast<Eigen::Index>(leaves.size());
      PatchRgb SL(L, 3);
      Eigen::VectorXd AL(L);
      for (Eigen::Index j = 0; j < L; ++j) {
        const auto e = static_cast<std::size_t>(leaves[static_cast<std::size_t>(j)]);
        SL.row(j) = S[e].transpose();
        AL(j) = tree.area[e];
      }
      // The oracle's shooter power: the unshot power of the shooter's whole patch (|S| pulled to the root).
      std::vector<Rgb> pulled(tree.size());
      for (std::size_t e = 0; e < tree.size(); ++e) pulled[e] = S[e].abs();
      pull(tree, pulled);
      const std::uint64_t b = static_cast<std::uint64_t>(r) << 32 | static_cast<std::uint64_t>(k);
      const StratifiedEmission emission(SL, AL, n, options.seed, b, StreamDomain::hierarchical_jacobi);
      if (!(emission.power() > 0)) break;
      // Trace in fixed chunks.
      const long chunk = std::max<long>(4096, (n + 63) / 64);
      const auto chunks = static_cast<std::size_t>((n + chunk - 1) / chunk);
      std::vector<std::vector<Deposit>> parts(chunks);
      parallel_for(
          chunks,
          [&](std::size_t c) {
            const long begin = static_cast<long>(c) * chunk, end = std::min(n, begin + chunk);
            constexpr long kBatch = 16;
            Ray rays[kBatch];
            Hit hits[kBatch];
            std::size_t from[kBatch];
            for (long w0 = begin; w0 < end; w0 += kBatch) {
              const long m = std::min(kBatch, end - w0);
              for (long q = 0; q < m; ++q) {
                const long w = w0 + q;
                const std::size_t j = emission.patch_of(w);
                const auto e = static_cast<std::size_t>(leaves[j]);
                const auto root = static_cast<std::size_t>(tree.root[e]);
                const std::array<float, 4> u = emission.first_uniforms(w, j);
                const Vec3 x = element_point(tree, e, u[0], u[1]);
                const Vec3 dir = Frame(roots.normal[root]).to_world(sample_cosine_hemisphere(u[2], u[3]));
                rays[q] = spawn_ray(offset[root], x, dir);
                from[q] = j;
              }
              visibility.intersect(rays, hits, static_cast<std::size_t>(m));
              for (long q = 0; q < m; ++q) {
                const Hit& hit = hits[q];
                if (hit.missed() || !hit.front) continue;
                const auto h = static_cast<std::size_t>(hit.patch);
                if (!(rho_max[h] > 0) && !options.clusters) continue;
                const std::size_t j = from[q];
                const auto e = static_cast<std::size_t>(leaves[j]);
                const auto root = static_cast<std::size_t>(tree.root[e]);
                Deposit dep;
                dep.patch = hit.patch;
                dep.point = rays[q].origin + hit.t * rays[q].direction;
                dep.incident = emission.weight(j) / static_cast<double>(n);
                dep.power = roots.rho[h] * dep.incident;
                dep.cap = rho_max[h] * tree.area[root] * pulled[root].maxCoeff();
                dep.shooter = static_cast<ElementIndex>(e);
                parts[c].push_back(dep);
              }
            }
          },
          1);
      // The oracle's descents in ray order.
      std::vector<Rgb> gathered(tree.size(), Rgb::Zero());
      std::vector<ClusterIrradiance> G(clusters.size(), ClusterIrradiance::Zero());
      std::vector<Vec3> centre(tree.size());
      for (std::size_t e = 0; e < tree.size(); ++e) centre[e] = centre_of(tree, e);
      for (const auto& part : parts)
        for (const Deposit& dep : part) {
          auto e = static_cast<std::size_t>(dep.patch);
          const Vec3& normal = roots.normal[e];
          const auto l = static_cast<std::size_t>(dep.shooter);
          const Vec3& n_l = roots.normal[static_cast<std::size_t>(tree.root[l])];
          if (options.clusters) {
            // The coarsest cluster of the hit patch that may receive from this shooter takes the ray (cluster_tree.h).
            chain.clear();
            for (std::int32_t c = clusters.leaf_of[e]; c >= 0; c = clusters.parent[static_cast<std::size_t>(c)])
              chain.push_back(c);
            bool taken = false;
            Vec3 w;
            for (auto it = chain.rbegin(); it != chain.rend() && !taken; ++it)
              if (cluster_receives(clusters, static_cast<std::size_t>(*it), centre[l], options.cluster_ratio, &w)) {
                cluster_deposit(clusters, static_cast<std::size_t>(*it), dep.incident, w, G);
                ++result.cluster_deposits;
                taken = true;
              }
            if (taken || !(rho_max[e] > 0)) continue;
          }
          while (!options.transport_oracle && !tree.is_leaf(e))
            e = static_cast<std::size_t>(tree.child_containing(e, dep.point, normal));
          while (options.transport_oracle) {
            const double T = transfer(tree, centre, l, e, n_l, normal, dep.cap);
            if (!(T > result.epsilon) || !within_depth(tree, e, options)) break;
            if (tree.is_leaf(e)) {
              split(e, r, gathered);
              for (std::size_t x = centre.size(); x < tree.size(); ++x) centre.push_back(centre_of(tree, x));
            }
            e = static_cast<std::size_t>(tree.child_containing(e, dep.point, normal));
          }
          gathered[e] += dep.power / tree.area[e];
        }
      result.rays += n;
      ++result.iterations;
      if (options.clusters) {
        // What the clusters received, to their members' root elements (radiosity rho_i H_i), then down the trees.
        const std::vector<Rgb> H = cluster_push(clusters, roots, G);
        for (std::size_t i = 0; i < N; ++i) gathered[i] += roots.rho[i] * H[i];
      }
      push(tree, gathered);
      S.assign(tree.size(), Rgb::Zero());
      for (std::size_t e = 0; e < tree.size(); ++e)
        if (tree.is_leaf(e)) {
          S[e] = gathered[e];
          B[e] += gathered[e];
        }
      result.memory_bytes = std::max(result.memory_bytes,
                                     tree.memory_bytes() + tree.size() * sizeof(Rgb) * (static_cast<std::size_t>(r) + 5) +
                                         static_cast<std::size_t>(n) * sizeof(Deposit) + clusters.memory_bytes() +
                                         G.capacity() * sizeof(ClusterIrradiance));
    }
  }

  // Every replicate at the final leaves (elements created after a replicate finished took its parent's value).
  result.leaves = tree.leaves();
  const auto L = static_cast<Eigen::Index>(result.leaves.size());
  std::vector<PatchRgb> BL(static_cast<std::size_t>(R), PatchRgb(L, 3));
  result.D.resize(L, 3);
  PatchRgb Dv(L, 3);
  for (Eigen::Index j = 0; j < L; ++j) {
    const auto e = static_cast<std::size_t>(result.leaves[static_cast<std::size_t>(j)]);
    for (int r = 0; r < R; ++r) {
      std::vector<Rgb>& B = Bs[static_cast<std::size_t>(r)];
      // A replicate that had nothing to shoot never grew its array past the tree it started from.
      if (B.size() < tree.size()) {
        const std::size_t old = B.size();
        B.resize(tree.size(), Rgb::Zero());
        for (std::size_t x = old; x < tree.size(); ++x) B[x] = B[static_cast<std::size_t>(tree.parent[x])];
      }
      BL[static_cast<std::size_t>(r)].row(j) = B[e].transpose();
    }
    result.D.row(j) = D[e].transpose();
    Dv.row(j) = Dvar[e].transpose();
  }
  const ReplicateEstimate est = replicate_estimate(BL, std::max<long>(options.particles, 1));
  result.B = est.B;
  result.B_se = (est.se.square() + Dv).sqrt();
  result.var = est.var;
  result.seconds = timer.seconds();
  return result;
}

}  // namespace radwalk
