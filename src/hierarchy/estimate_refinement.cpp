#include "hierarchy/estimate_refinement.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

#include "core/error.h"
#include "core/timer.h"
#include "hierarchy/leaf_patches.h"
#include "hierarchy/leaf_variation.h"
#include "solve/discretisation_error.h"
#include "solve/problem.h"
#include "visibility/embree_visibility.h"

namespace radwalk {

LeafErrorIndicator leaf_error_indicator(const PatchSet& roots, const Visibility& visibility, const ElementTree& tree,
                                        const std::vector<ElementIndex>& leaf_ids, const PatchRgb& B,
                                        const PatchRgb& B_disc, int directions, int points_side, std::uint64_t seed) {
  LeafErrorIndicator out;
  const PatchSet leaves = leaf_patches(roots, tree, leaf_ids);
  const LeafVariation var = leaf_variation(roots, visibility, tree, leaf_ids, B, points_side, directions, seed);
  out.B_disc = B_disc;
  out.rays = var.rays;
  out.eta2.assign(leaf_ids.size(), 0.0);
  double total = 0, disc_part = 0, norm = 0;
  for (std::size_t k = 0; k < leaf_ids.size(); ++k) {
    const auto r = static_cast<Eigen::Index>(k);
    const double A = leaves.area[k];
    const double d2 = B_disc.row(r).square().sum();
    const double w2 = var.W2.row(r).cwiseMax(0.0).sum();
    out.eta2[k] = A * (d2 + w2);
    if ((leaves.E[k] > 0).any() || !(leaves.rho[k] > 0).any()) continue;
    total += out.eta2[k];
    disc_part += A * d2;
    norm += A * B.row(r).square().sum();
  }
  out.eta = norm > 0 ? std::sqrt(total / norm) : 0.0;
  out.disc_share = total > 0 ? disc_part / total : 0.0;
  return out;
}

LeafErrorIndicator estimate_leaf_errors(const PatchSet& roots, const Visibility& visibility, const HierarchicalResult& h,
                                        int directions, int points_side, std::uint64_t seed,
                                        bool attribute_shooters) {
  const PatchSet leaves = leaf_patches(roots, h.tree, h.leaves);
  const EmbreeVisibility leaf_visibility(leaves);
  const auto n = static_cast<Eigen::Index>(leaves.size());
  const RadiosityProblem problem = make_problem(leaves, SparseF(n, n));  // no stored F: the estimate's own rays give H
  ShooterAttribution attribution;
  const DiscretisationError disc =
      discretisation_error(leaves, leaf_visibility, problem, h.B, directions, seed,
                           attribute_shooters ? &attribution : nullptr);
  if (attribute_shooters) {
    LeafErrorIndicator out;
    out.B_disc = disc.standard_error;
    out.shooter_share = std::move(attribution.share);
    out.rays = disc.rays;
    out.eta2.assign(leaves.size(), 0.0);
    double total = 0, norm = 0;
    for (std::size_t k = 0; k < leaves.size(); ++k) {
      const auto r = static_cast<Eigen::Index>(k);
      out.eta2[k] = leaves.area[k] * out.B_disc.row(r).square().sum();
      if ((leaves.E[k] > 0).any() || !(leaves.rho[k] > 0).any()) continue;
      total += out.eta2[k];
      norm += leaves.area[k] * h.B.row(r).square().sum();
    }
    out.eta = norm > 0 ? std::sqrt(total / norm) : 0.0;
    out.disc_share = 1;
    return out;
  }
  LeafErrorIndicator out = leaf_error_indicator(roots, visibility, h.tree, h.leaves, h.B, disc.standard_error,
                                                directions, points_side, seed);
  out.rays += disc.rays;
  return out;
}

EstimateRefinementResult refine_by_estimate(const PatchSet& roots, const Visibility& visibility,
                                            const HierarchicalOptions& solve, const EstimateRefinementOptions& o) {
  if (o.steps < 0) throw InputError("--hierarchical-steps must be >= 0");
  if (!(o.target >= 0) || !std::isfinite(o.target)) throw InputError("--hierarchical-target must be a finite number >= 0");
  if (!(o.split_share > 0 && o.split_share <= 1)) throw InputError("the split share must be in (0, 1]");
  if (o.rays_per_leaf < 1 || o.directions < 1 || o.points_side < 2)
    throw InputError("refinement by the estimate: rays per leaf and directions must be >= 1, points per side >= 2");
  EstimateRefinementResult result;
  ElementTree tree = make_element_tree(roots);
  for (int s = 0;; ++s) {
    const Timer timer;
    HierarchicalOptions so = solve;
    const long leaves_now = static_cast<long>(tree.leaves().size());
    // A step that will be the last whatever the estimate says (the budget or the steps are used up) gets every ray.
    const bool last = s >= o.steps || (o.max_leaves > 0 && leaves_now + 3 > o.max_leaves);
    so.particles = last ? solve.particles : std::min(solve.particles, std::max<long>(1, o.rays_per_leaf * leaves_now));
    so.seed = solve.seed + 7919 * static_cast<std::uint64_t>(s);
    HierarchicalResult h = solve_hierarchical(roots, visibility, std::move(tree), so);
    if (last) {  // no estimate: nothing would be split after it (the caller may estimate B_disc on the result)
      EstimateRefinementStep step;
      step.leaves = static_cast<long>(h.leaves.size());
      step.eta = std::numeric_limits<double>::quiet_NaN();
      step.rays = h.rays + h.shadow_rays;
      step.seconds = timer.seconds();
      result.steps.push_back(step);
      result.solution = std::move(h);
      return result;
    }
    const Timer estimate_timer;
    const LeafErrorIndicator ind = estimate_leaf_errors(roots, visibility, h, o.directions, o.points_side, so.seed);
    const double estimate_seconds = estimate_timer.seconds();
    EstimateRefinementStep step;
    step.leaves = static_cast<long>(h.leaves.size());
    step.eta = ind.eta;
    step.disc_share = ind.disc_share;
    step.estimate_seconds = estimate_seconds;
    step.rays = h.rays + h.shadow_rays + ind.rays;
    result.reached = o.target > 0 && ind.eta <= o.target;
    const bool budget = o.max_leaves > 0 && step.leaves + 3 > o.max_leaves;
    if (result.reached || budget || s >= o.steps) {
      step.seconds = timer.seconds();
      result.steps.push_back(step);
      if (so.particles < solve.particles) {
        const Timer final_timer;
        so.particles = solve.particles;
        result.solution = solve_hierarchical(roots, visibility, std::move(h.tree), so);
        EstimateRefinementStep again;  // the final tree solved again with every ray, as a step of its own
        again.leaves = static_cast<long>(result.solution.leaves.size());
        again.eta = std::numeric_limits<double>::quiet_NaN();
        again.rays = result.solution.rays + result.solution.shadow_rays;
        again.seconds = final_timer.seconds();
        result.steps.push_back(again);
      } else {
        result.solution = std::move(h);
        result.B_disc = ind.B_disc;
      }
      return result;
    }
    // Split the leaves with the largest eta_l^2 until they hold split_share of the total.
    std::vector<std::size_t> order(h.leaves.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return ind.eta2[a] > ind.eta2[b]; });
    const double total = std::accumulate(ind.eta2.begin(), ind.eta2.end(), 0.0);
    double held = 0;
    long leaves = step.leaves;
    tree = std::move(h.tree);
    for (const std::size_t k : order) {
      if (step.split > 0 && held >= o.split_share * total) break;
      if (o.max_leaves > 0 && leaves + 3 > o.max_leaves) break;
      if (!(ind.eta2[k] > 0)) break;
      const auto e = static_cast<std::size_t>(h.leaves[k]);
      if (!splittable(tree, e, solve)) continue;
      tree.split(e);
      held += ind.eta2[k];
      leaves += 3;
      ++step.split;
    }
    step.seconds = timer.seconds();
    result.steps.push_back(step);
    if (step.split == 0) {  // nothing can be split: solve the tree as it is with all the rays
      const Timer final_timer;
      so.particles = solve.particles;
      result.solution = solve_hierarchical(roots, visibility, std::move(tree), so);
      EstimateRefinementStep again;
      again.leaves = static_cast<long>(result.solution.leaves.size());
      again.eta = std::numeric_limits<double>::quiet_NaN();
      again.rays = result.solution.rays + result.solution.shadow_rays;
      again.seconds = final_timer.seconds();
      result.steps.push_back(again);
      return result;
    }
  }
}

}  // namespace radwalk
