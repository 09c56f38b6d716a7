// Refinement by the a-posteriori estimate (hierarchy/estimate_refinement.h, hierarchy/leaf_variation.h):
//   - furnace: a closed cube whose walls all emit E and reflect rho has the constant solution B = E / (1 - rho), so
//     every leaf of whatever tree the (noise-driven) refinement makes has that expectation: every leaf passes a
//     t-test against it (replicate standard errors, family-wise alpha = 1e-3, Sidak over leaves and channels), and
//     the within-leaf variation is 0 in expectation (its mean over the leaves is within 4 standard errors of 0);
//   - contact line: a block standing on the floor of a room lit from the ceiling, refined to 1000 leaves: the
//     floor's leaves within 0.15 of the block's foot (the contact line, either side) end at least one level deeper
//     on average than the floor's leaves more than 0.45 from it (measured: 5.1 against 3.1; a refinement blind to
//     the contact, uniform, would give equal levels);
//   - convergence to the path tracer: per input face, the area-weighted mean of the leaves against the path
//     tracer's face average (no discretisation error, only its own noise). Unrefined (the input faces as leaves)
//     the differences stand out of the statistical errors (some face's z beyond the Sidak critical value at
//     family-wise 1e-3: the discretisation error is visible); refined to 600 leaves every face agrees within
//     z_crit x sqrt(se_h^2 + se_pt^2 + disc^2) (disc: the leaves' B_disc summed over the face, a bound whatever
//     their correlation) and the RMS relative difference falls.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "hierarchy_test_scenes.h"
#include "hierarchy/estimate_refinement.h"
#include "hierarchy/leaf_patches.h"
#include "hierarchy/leaf_variation.h"
#include "pathtrace/patch_average.h"
#include "patch/patch_builder.h"
#include "solve/discretisation_error.h"
#include "solve/problem.h"
#include "support/box_scenes.h"
#include "support/stat_checks.h"
#include "support/statistics.h"
#include "visibility/embree_visibility.h"

using namespace radwalk;

namespace {

// The room [0, 2]^3 (inward, one face per wall, rho 0.6), a light [0.75, 1.25]^2 facing down at z = 1.99, and a
// block [0.6, 1.4]^2 x [0, 0.5] standing on the floor (outward, rho 0.5).
PatchSet block_room() {
  PatchBuilder b;
  const int wall = b.add_material("wall", Rgb::Constant(0.6));
  const int light = b.add_material("light", Rgb::Zero(), Rgb::Constant(10.0));
  const int block = b.add_material("block", Rgb::Constant(0.5));
  test::add_box(b, Vec3(0, 0, 0), Vec3(2, 2, 2), 1, true, wall);
  b.add_quad(Vec3(0.75, 0.75, 1.99), Vec3(0.75, 1.25, 1.99), Vec3(1.25, 1.25, 1.99), Vec3(1.25, 0.75, 1.99), light);
  test::add_box(b, Vec3(0.6, 0.6, 0), Vec3(1.4, 1.4, 0.5), 1, false, block);
  return b.build();
}

Vec3 centre(const ElementTree& t, std::size_t e) {
  Vec3 c = Vec3::Zero();
  for (int k = 0; k < t.corner_count[e]; ++k) c += t.corner[e][static_cast<std::size_t>(k)];
  return c / t.corner_count[e];
}

HierarchicalOptions leaves_only(long particles, int replicates, std::uint64_t seed) {
  HierarchicalOptions o;
  o.max_level = 6;
  o.particles = particles;
  o.replicates = replicates;
  o.seed = seed;
  o.direct_oracle = o.transport_oracle = false;
  return o;
}

}  // namespace

TEST_CASE("estimate refinement: furnace, every leaf unbiased for B = E / (1 - rho) and no variation", "[hierarchy]") {
  const double rho = 0.5, Le = 1 / kPi;  // E = 1, B = 2
  const PatchSet roots = test::furnace(rho, Le);
  const EmbreeVisibility visibility(roots);
  EstimateRefinementOptions e;
  e.max_leaves = 60;
  e.rays_per_leaf = 2000;
  const EstimateRefinementResult r = refine_by_estimate(roots, visibility, leaves_only(48000, 24, 7), e);
  const HierarchicalResult& h = r.solution;
  INFO("leaves " << h.leaves.size() << ", steps " << r.steps.size());
  REQUIRE(h.leaves.size() > roots.size());
  const auto L = static_cast<std::size_t>(h.B.rows());
  const double t_crit = test::t_critical(z_critical(sidak(1e-3, 3 * L)), 23);
  test::ZTable table("furnace leaves", t_crit);
  const double B = Le * kPi / (1 - rho);
  for (std::size_t k = 0; k < L; ++k)
    for (int c = 0; c < 3; ++c)
      table.add("leaf " + std::to_string(k), h.B(static_cast<Eigen::Index>(k), c),
                h.B_se(static_cast<Eigen::Index>(k), c), B);
  table.check();
  // The variation estimate is a cross-replicate covariance: 0 in expectation on a constant field. Its leaves are
  // independent (each its own streams): the mean over leaves is within 4 of its standard errors of 0.
  const LeafVariation v = leaf_variation(roots, visibility, h.tree, h.leaves, h.B, 2, 16, 11);
  const Eigen::ArrayXd w = v.W2.col(0);
  const double mean = w.mean(), se = std::sqrt((w - mean).square().sum() / (w.size() - 1) / w.size());
  INFO("mean W2 " << mean << " +- " << se);
  CHECK(std::abs(mean) <= 4 * se + 1e-12);
}

TEST_CASE("estimate refinement: the floor along a block's foot is refined deeper than far from it", "[hierarchy]") {
  const PatchSet roots = block_room();
  const EmbreeVisibility visibility(roots);
  EstimateRefinementOptions e;
  e.max_leaves = 1000;
  e.steps = 40;
  const EstimateRefinementResult r = refine_by_estimate(roots, visibility, leaves_only(200000, 4, 3), e);
  const ElementTree& t = r.solution.tree;
  double near_sum = 0, far_sum = 0;
  int near_n = 0, far_n = 0;
  for (const ElementIndex l : r.solution.leaves) {
    const auto x = static_cast<std::size_t>(l);
    const Vec3 c = centre(t, x);
    if (std::abs(c.z()) > 1e-9 || std::abs(roots.normal[static_cast<std::size_t>(t.root[x])].z() - 1) > 1e-9) continue;
    // Distance from the centre to the block's foot, the boundary of the footprint [0.6, 1.4]^2 (either side).
    const double dx = std::max({0.6 - c.x(), 0.0, c.x() - 1.4}), dy = std::max({0.6 - c.y(), 0.0, c.y() - 1.4});
    const double inside = std::min({c.x() - 0.6, 1.4 - c.x(), c.y() - 0.6, 1.4 - c.y()});
    const double d = inside > 0 ? inside : std::hypot(dx, dy);
    if (d < 0.15) {
      near_sum += t.level[x];
      ++near_n;
    } else if (d > 0.45 && inside <= 0) {
      far_sum += t.level[x];
      ++far_n;
    }
  }
  INFO("floor leaves near the foot " << near_n << " (mean level " << near_sum / std::max(near_n, 1) << "), far "
                                     << far_n << " (mean level " << far_sum / std::max(far_n, 1) << ")");
  REQUIRE(near_n > 0);
  REQUIRE(far_n > 0);
  CHECK(near_sum / near_n >= far_sum / far_n + 1);
}

TEST_CASE("estimate refinement: the face averages converge to the path tracer's", "[hierarchy]") {
  const PatchSet roots = block_room();
  const EmbreeVisibility visibility(roots);
  PatchAverageOptions pt;
  pt.spp = 1 << 15;
  pt.seed = 101;
  pt.progress = false;
  const Solution ref = estimate_patch_averages(roots, visibility, pt);
  const std::size_t N = roots.size();
  // Per face and channel: (mean of the leaves - the path tracer) and its bound sqrt(se_h^2 + se_pt^2 + disc^2).
  const auto compare = [&](long budget, long particles, double* rms, double* max_z_stat, double* max_z_all) {
    EstimateRefinementOptions e;
    e.max_leaves = budget;
    e.rays_per_leaf = 500;
    const EstimateRefinementResult r = refine_by_estimate(roots, visibility, leaves_only(particles, 4, 5), e);
    const HierarchicalResult& h = r.solution;
    const PatchSet leaves = leaf_patches(roots, h.tree, h.leaves);
    const EmbreeVisibility leaf_visibility(leaves);
    const auto n = static_cast<Eigen::Index>(leaves.size());
    const DiscretisationError disc =
        discretisation_error(leaves, leaf_visibility, make_problem(leaves, SparseF(n, n)), h.B, 16, 9);
    std::vector<Rgb> sum(N, Rgb::Zero()), se(N, Rgb::Zero()), dsum(N, Rgb::Zero());
    for (std::size_t k = 0; k < leaves.size(); ++k) {
      const auto f = static_cast<std::size_t>(h.tree.root[static_cast<std::size_t>(h.leaves[k])]);
      const auto i = static_cast<Eigen::Index>(k);
      sum[f] += leaves.area[k] * h.B.row(i).transpose();
      se[f] += leaves.area[k] * h.B_se.row(i).transpose();  // sum of sds: a bound whatever the correlation
      dsum[f] += leaves.area[k] * disc.standard_error.row(i).transpose();
    }
    double r2 = 0, norm = 0;
    *max_z_stat = *max_z_all = 0;
    for (std::size_t f = 0; f < N; ++f) {
      if (!(roots.rho[f] > 0).any() || !(ref.B.row(static_cast<Eigen::Index>(f)).maxCoeff() > 0)) continue;
      for (int c = 0; c < 3; ++c) {
        const double mean = sum[f](c) / roots.area[f], pt_b = ref.B(static_cast<Eigen::Index>(f), c);
        const double s_h = se[f](c) / roots.area[f], s_pt = ref.B_se(static_cast<Eigen::Index>(f), c);
        const double s_d = dsum[f](c) / roots.area[f];
        const double d = mean - pt_b;
        r2 += roots.area[f] * d * d;
        norm += roots.area[f] * pt_b * pt_b;
        *max_z_stat = std::max(*max_z_stat, std::abs(d) / std::sqrt(s_h * s_h + s_pt * s_pt));
        *max_z_all = std::max(*max_z_all, std::abs(d) / std::sqrt(s_h * s_h + s_pt * s_pt + s_d * s_d));
      }
    }
    *rms = std::sqrt(r2 / norm);
  };
  const double z_crit = z_critical(sidak(1e-3, 3 * N));
  double rms0, stat0, all0, rms1, stat1, all1;
  compare(static_cast<long>(N), 400000, &rms0, &stat0, &all0);
  compare(600, 900000, &rms1, &stat1, &all1);
  INFO("unrefined: RMS relative difference " << rms0 << ", largest z (statistical) " << stat0 << ", (with B_disc) "
                                             << all0 << "; refined: " << rms1 << ", " << stat1 << ", " << all1
                                             << "; z_crit " << z_crit);
  CHECK(stat0 > z_crit);  // unrefined, the discretisation error stands out of the statistical errors
  CHECK(all1 <= z_crit);  // refined, every face agrees within its stated errors
  CHECK(rms1 < rms0);
}
