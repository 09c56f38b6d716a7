#pragma once
// Refinement of the element trees by the a-posteriori error estimate (docs/theory/hierarchical_radiosity.md,
// "Refinement by the estimate"): solve, estimate each leaf's share of the error, split the leaves with the largest
// shares, solve again.
//
// The squared L2 error of a piecewise-constant solution B_h against the continuous radiosity B splits per leaf l
// (Pythagoras: B - Bbar_l is orthogonal to the constants on l) into
//   int_l |B - B_h|^2 = A_l |Bbar_l - B_hl|^2 + int_l |B - Bbar_l|^2 ~ A_l (|B_disc_l|^2 + |W2_l|),
// B_disc the discretisation estimate of the leaves as patches (solve/discretisation_error.h), W2 the within-leaf
// variation (leaf_variation.h, clamped at 0), |.| summed over the channels: the indicator
//   eta_l^2 = A_l sum_c (B_disc_lc^2 + max(W2_lc, 0)),
// and the estimated relative error eta = sqrt(sum_l eta_l^2 / sum_l A_l |B_hl|^2) over the reflecting, non-emitting
// leaves (the measure of bench/bench_hierarchical). Splitting l into its four quarters removes about 3/4 of eta_l^2
// where B is smooth on l (the variation of a gradient scales with the area) for 3 more elements, so the greedy rule
// splits the largest eta_l^2 first, and an optimal mesh for a given count has equal eta_l^2 (the Lagrange condition
// of minimising sum eta_l^2 at a fixed number of leaves).
//
// Step s: solve on the tree (solve_hierarchical, with the a-priori oracles as `solve` says), with min(particles,
// rays_per_leaf x leaves) rays; estimate eta_l; stop when eta <= target, the budget of leaves is reached or after
// `steps` splitting steps; else split the leaves in decreasing eta_l^2 until they hold `split_share` of sum eta_l^2
// (at least one; never past max_leaves, max_level or min_area), and repeat. A step known to be the last before it is
// solved (the budget or the steps used up) gets all `particles` and no estimate (its eta is NaN); when the last solve had fewer (the target was
// reached, or nothing could be split), the final tree is solved once more with all of them, recorded as a last step
// without an estimate. The estimate's rays are counted in the steps.
#include <cstdint>
#include <vector>

#include "hierarchy/hierarchical_jacobi.h"

namespace radwalk {

struct EstimateRefinementOptions {
  int steps = 12;             // splitting steps at most
  double target = 0;          // stop once the estimated relative error eta <= target (0: steps and budget only)
  long max_leaves = 0;        // budget of leaves (0: none)
  double split_share = 0.8;   // the share of sum eta_l^2 the leaves split in one step hold, in (0, 1]
  long rays_per_leaf = 300;   // the rays of a step's solve per leaf (capped by the solve's particles)
  int directions = 16;        // of B_disc and of the variation
  int points_side = 2;        // of the variation: m^2 points per leaf
};

struct EstimateRefinementStep {
  long leaves = 0;
  double eta = 0;       // the estimated relative L2 error of this step's solution
  double disc_share = 0;  // the share of sum eta_l^2 from B_disc (the rest: within-leaf variation)
  long split = 0;       // leaves split after it
  long rays = 0;        // the solve's and the estimate's
  double seconds = 0;   // wall seconds of the step
  double estimate_seconds = 0;  // of which the estimate's
};

struct EstimateRefinementResult {
  HierarchicalResult solution;  // on the final tree
  PatchRgb B_disc;              // per final leaf, from the last estimate (empty when the final solve had none)
  std::vector<EstimateRefinementStep> steps;
  bool reached = false;         // eta <= target at the last estimate
};

// The indicator of one solution h on the tree over `roots` (the definitions above): per leaf eta_l^2 (row k =
// h.leaves[k]), B_disc of the leaves as patches, eta and the B_disc share of sum eta_l^2 over the counted leaves,
// and the rays of both estimates. directions L >= 1, points_side m >= 2.
struct LeafErrorIndicator {
  std::vector<double> eta2;
  std::vector<double> shooter_share;  // each leaf's share of the squared error as a shooter (estimate_leaf_errors
                                      // when asked: solve/shooter_attribution.h); else empty
  PatchRgb B_disc;
  double eta = 0, disc_share = 0;
  long rays = 0;
};
// attribute_shooters: instead of the within-leaf variation, each leaf's shooter share (shooter_share; traces the
// discretisation estimate's fluctuation shots again; docs/theory/discretisation_error.md, "Refinement by both
// shares"): eta_l^2 is then A_l sum_c B_disc_lc^2 alone and the variation's rays are not traced.
LeafErrorIndicator estimate_leaf_errors(const PatchSet& roots, const Visibility& visibility, const HierarchicalResult& h,
                                        int directions, int points_side, std::uint64_t seed,
                                        bool attribute_shooters = false);

// The same indicator for any solution B on the leaves (row k = leaves[k]) whose B_disc is already estimated (e.g.
// by the form-factor route on the leaves as patches): eta_l^2 = A_l sum_c (B_disc_lc^2 + max(W2_lc, 0)), W2 from
// leaf_variation with points_side and directions; rays are the variation's only.
LeafErrorIndicator leaf_error_indicator(const PatchSet& roots, const Visibility& visibility, const ElementTree& tree,
                                        const std::vector<ElementIndex>& leaves, const PatchRgb& B,
                                        const PatchRgb& B_disc, int directions, int points_side, std::uint64_t seed);

EstimateRefinementResult refine_by_estimate(const PatchSet& roots, const Visibility& visibility,
                                            const HierarchicalOptions& solve, const EstimateRefinementOptions& options);

}  // namespace radwalk
