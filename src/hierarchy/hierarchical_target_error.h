#pragma once
// Accuracy on request through the element hierarchy: solve on the element trees in steps, refining the leaves by
// the a-posteriori estimate, until the estimated total error is at most a target (docs/accuracy.md, "Accuracy on
// request"; docs/hierarchy.md, "Accuracy on request through the hierarchy").
//
// Step s on the current tree (leaves = the elements without children):
//   1. solve (solve_hierarchical with both a-priori oracles off: the leaves act as patches, the ordinary stochastic
//      Jacobi's unbiased estimate of their discrete system) with R_s rays per leaf, R_s x leaves in all, seed
//      solve.seed + 7919 s, and m_s = max(m, ceil(sqrt(R_s / (2 K)))) direct-light points per leaf side (at most
//      64, K the emitters): the direct light is one estimate shared by the replicates, its variance falls as
//      1 / m_s^2 and not with the rays, so with m fixed the statistical part stops falling at the direct light's
//      floor while the plan keeps adding rays (measured on the Cornell box, 300 leaves, 1000 rays a leaf: 3.9 %
//      statistical with 16 points, 1.6 % with 256); with M_s = R_s / (2 K) its 2 shadow rays per point and emitter
//      cost as much as the shooting;
//   2. estimate per leaf B_se (the replicates' spread, with the direct light's variance), B_disc (the
//      discretisation estimate of the leaves as patches, solve/discretisation_error.h) and the refinement
//      indicators: each leaf's shooter share c_l (solve/shooter_attribution.h) and the receiver share
//      eta_l^2 = A_l sum_c B_disc_lc^2; when the shooter shares are not estimated (a leaf solver that gives none),
//      eta_l^2 = A_l sum_c (B_disc_lc^2 + max(W2_lc, 0)) (estimate_refinement.h: W2 the within-leaf variation,
//      the part of the L2 error B_disc does not hold; with the shooter shares only the part of it that the
//      leaves' averages see counts, which c_l holds: docs/theory/discretisation_error.md, "Refinement by both
//      shares");
//   3. the errors over the reflecting non-emitting leaves, the same definitions as the uniform --target-error's
//      (solve/target_error.h, relative_error): statistical e_s (B_se), discretisation e_d (B_disc), total e
//      (sqrt(B_se^2 + B_disc^2)). Stop when e <= E;
//   4. else the plan of solve/target_error.h (plan_target_error_step, the same rules): where the discretisation
//      part dominates, the leaves with the largest eta_l^2 are split in 4 until they hold the plan's share of
//      sum eta_l^2, and so are those with the largest c_l until they hold that share of sum max(c_l, 0)
//      (solve/refinement_marks.h) (a leaf at max_level or below 4 min_area is skipped; a leaf within its equal
//      share of the target, eta_l^2 (or c_l) <= (kPlanTarget E)^2 sum_l A_l |B_l|^2 / N, is never split: the
//      optimal mesh equidistributes the error, and far from the target the share is 1), and the share is capped
//      at the bulk parameter theta (options.bulk, Doerfler's marking: the fewest leaves that hold theta of the sum,
//      however far the error is above its target; below); where the statistical part is above its target, R grows
//      by the plan's factor.
// Split kind (options.split "adaptive"): before splitting, the leaves marked in step 4 get their directional variation
// estimated (its rays are the step's) and each is split as hierarchy/split_kind.h chooses; the start splits by edge
// length (below).
// The stopping and the budgets are the uniform route's: e is judged on B_disc (the error of each leaf's average,
// what the per-element benchmark measures), while the indicator that picks the leaves also weighs the variation
// inside them (a leaf straddling a shadow line has a small B_disc but a large W2). max_leaves bounds the leaves;
// no step is started when the elapsed time plus the last step's time scaled by (leaves' R') / (leaves R) would
// pass max_seconds (0: none); at most max_steps solves. When a budget stops the run first, `reached` is false and
// stop_reason names it ("max-leaves", "max-seconds", "max-steps", "rays"), or "depth" when the budget had room but
// no leaf the plan marked may be split (HierarchicalOptions' max_level and min_area: within_depth); the last
// solution (the most accurate) is kept with its own estimates.
// start_leaves > 0: before the first step the trees are split by edge length to the roots and about start_leaves
// leaves more, within max_leaves, with bands where the split is adaptive (hierarchy/start_by_edge_length.h; the
// uniform route starts by area, solve/target_error.h).
//
// Transport. Step 1 above is the hierarchy's own ("rays": hierarchical stochastic Jacobi) unless a leaf solver
// `leaf_work` is given ("form factors"): then step 1 turns the current leaves into patches (leaf_patches.h, leaf k =
// patch k) and hands them with R rays a leaf to leaf_work, which solves them as the uniform route solves its patches
// (traced F with the emitter columns exact, the automatic solver) and returns B with B_se and B_disc estimated as
// the uniform route estimates them; step 2 then adds only W2 to that B_disc (leaf_error_indicator). The element
// trees, the start, the indicator, the splitting and the plan are the same for both transports; only how the
// leaves' B, B_se and B_disc are obtained differs. A step whose solve did not converge stops the run ("solver").
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "hierarchy/hierarchical_jacobi.h"
#include "solve/target_error.h"

namespace radwalk {

// The bulk parameter theta: Doerfler's marking (Doerfler 1996; with theta small enough it gives meshes of
// quasi-optimal size, Cascon, Kreuzer, Nochetto and Siebert 2008) splits the fewest elements holding theta of
// the summed indicator and re-estimates. Uncapped (the plan's share is 1 whenever e_d >= sqrt(2) t_d) a step
// split every leaf above the equal share: on the spot-lit room, whose error sits in a few mm-sized wall
// leaves at the floor beside the light, a step from 2,776 leaves split 1,074 and the 6,000-leaf budget ran
// out at 2.3 % (seed 3); with theta = 0.7 the four seeds reach 1 % with 1,114-1,198 leaves in 7-9 steps, and
// the Cornell box takes 439-601 leaves for 0.01 where it took 727-847 (docs/hierarchy.md, "Doerfler's
// marking"). The groups' plans (options.each) are not capped: they hold each group's mean, whose error is
// spread over the group.
inline constexpr double kBulkFraction = 0.7;

struct HierarchicalTargetOptions {
  double target = 0.01;      // E, in (0, 1)
  long rays_per_leaf = 1000;  // R of the first step (>= 1)
  long max_leaves = 20000;
  double max_seconds = 0;    // 0: no limit
  int max_steps = 12;
  std::size_t start_leaves = 0;
  double bulk = kBulkFraction;  // theta in (0, 1] (1: the plan's share uncapped)
  int directions = 16;       // of B_disc and of W2 (>= 1)
  int points_side = 2;       // of W2: m^2 points per leaf (>= 2)
  // "": the per-leaf target only; "material", "object" or "group": also each such group's mean within E (as the
  // uniform route, solve/target_error.h: the leaves with the largest shares of a group's error are split). Form-factor transport only:
  // the group means' errors need the adjoint of a stored F.
  std::string each;
  // "regular": every split regular; "adaptive": each split's kind by hierarchy/split_kind.h, the start's by edge
  // length (start_leaves) and each step's from the directional variation (leaf_directional_variation, m = max(points_side,
  // 4) per side, `directions` directions, seed the step's + 1) estimated for the leaves marked for splitting only.
  std::string split = "regular";
};

// One step: the uniform route's record (patches = leaves, rays_per_patch = rays per leaf) and the rays traced in
// all (the solve's, its shadow rays and the estimates').
struct HierarchicalTargetStep {
  TargetErrorStep step;
  long band_splits = 0;         // of step.split, those in bands (adaptive split)
  long rays = 0;
  double estimate_seconds = 0;  // of step.seconds, the estimates'
};

struct HierarchicalTargetResult {
  HierarchicalResult solution;  // the last step's, on its tree (with form factors: tree, leaves, B and B_se only)
  PatchRgb B_disc;              // its leaves' (row k = solution.leaves[k])
  std::vector<HierarchicalTargetStep> steps;
  std::vector<GroupMeanError> groups;  // the last step's, with `each` (else empty)
  bool reached = false;
  std::string stop_reason;      // "target reached", "max-leaves", "depth", "max-seconds", "max-steps", "rays", "solver"
  double seconds = 0;
  // With form factors: the last step's stage on its leaves as patches (F and the solver's Solution, with B_se and
  // B_disc); empty F and default Solution with rays.
  bool form_factor_transport = false;
  TargetErrorStage stage;
};

// The last step's solution on its leaves (row k = leaf k), as every solver reports one. Rays: B, B_se, B_disc and
// the hierarchical solve's counts, method "hierarchical-jacobi", converged (its run ends when the unshot power is
// below 1e-6 of the first shot's, or after 200 iterations per replicate). Form factors: the leaf solver's Solution
// as it returned it (its method, status, B, B_se, B_disc).
Solution hierarchical_target_solution(const HierarchicalTargetResult& result);

// solve: the hierarchical solve's options (its particles and oracles are set per step here; with form factors
// only max_level, min_area and seed are read). InputError for options out of range, `each` with the rays
// transport, max_leaves below the roots'
// count, or a leaf solver that returns no B_disc. on_step, if set, is called after each step. leaf_work empty:
// rays; set: form factors (above).
HierarchicalTargetResult solve_hierarchical_to_target_error(
    const PatchSet& roots, const Visibility& visibility, const HierarchicalOptions& solve,
    const HierarchicalTargetOptions& options,
    const std::function<void(const HierarchicalTargetStep&, int step)>& on_step = {},
    const TargetErrorWork& leaf_work = {});

}  // namespace radwalk
