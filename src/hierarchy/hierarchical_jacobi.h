#pragma once
// Hierarchical stochastic Jacobi (Bekaert's hierarchical Monte Carlo radiosity; docs/theory/
// hierarchical_radiosity.md): stochastic Jacobi's incremental shooting (walk/stochastic_jacobi.h) from the leaves of
// an element tree, each ray's receiver element picked at its end point by a refinement oracle, no links stored.
//
// 1. The direct light D per element, exact where unoccluded, with the tree refined by the direct light's own
//    fluctuation (direct_refinement.h); epsilon = tol * Phi_E, Phi_E = max_c sum_i A_i E_ic the emitted power.
// 2. Replicate r = 0 .. R-1: B_r = E + D and S_0 = D at the leaves; iteration k: the leaves' unshot power
//    Phi_k = sum_l A_l sum_c |S_lc|, n_k = max(16, round(c Phi_k)) rays (c = n_r (1 - rho_bar) / Phi_0, n_r the
//    replicate's share of `particles`), allocated and stratified over the leaves by StratifiedEmission(S_k, A, n_k)
//    (walk/stratified_emission.h, domain hierarchical_jacobi, b = r << 32 | k): a ray from leaf l leaves a
//    uniform point x of l along a cosine direction and carries W_l = A_l S_kl / pi_l (pi_l = its share of Phi_k).
//    At its first hit y on the front of input patch h (reflectance rho_h) the oracle descends h's tree from the
//    root: from element e it goes to the child containing y while
//       T_e = max_c rho_hc * P_l * min(1, A_e cos_x cos_y / (pi d^2)) * min(1, sqrt(A_e) / d) > epsilon,
//       level(e) < max_level and A_e / 4 >= min_area,
//    d, cos_x, cos_y from the centre of the shooter leaf l to the centre of e (not from the ray's own points: every
//    ray of one shooter landing in e must take the same decision at e, or power moves between e's children and the
//    estimate is biased; the furnace test caught that), P_l = A_p max_c |S_k|_pc the unshot power of the shooter's
//    whole patch p (|S_k| pulled to p's root: the rays of all p's leaves together carry the transfer from p, so how
//    finely p is split must not change the receiver's level), min(1, A_e cos cos / (pi d^2)) the point-to-disc
//    estimate of the form factor and sqrt(A_e) / d the kernel's relative variation over e (a constant over e
//    misplaces about the transfer times that variation); a leaf is split when the oracle asks for a child that does
//    not exist yet, and the element e it
//    stops at gathers rho_h W_l / (n_k A_e). Then push (push_pull.h): every leaf's S_{k+1} is the sum of what it
//    and its ancestors gathered, and B_r += S_{k+1}. Stop once Phi_k <= 1e-6 Phi_0 (or after 200 iterations).
//    Given S_k and the tree, E[S_{k+1}] at leaf l is rho times the average over the element e(l, ray) the oracle
//    picked of the irradiance of S_k's shooting: exactly the discrete hierarchical operator, so B_r is unbiased
//    for the hierarchical system's solution; its difference from the leaves' true averages is the discretisation
//    error of the elements the oracle stopped at, which the oracle bounds by epsilon per transfer.
// 3. New leaves (a split during replicate r) take their parent's B in every replicate finished or running, and its
//    D: a finished replicate's value at the parent was its estimate over the whole parent.
// B = mean_r B_r per leaf, B_se^2 = the replicates' spread / R + var(D) (the direct light is one estimate shared by
// the replicates, direct_refinement.h). Rays are traced in parallel chunks; the oracle's descents and the splits
// are done in ray order afterwards: the result does not depend on the thread count.
#include <cstdint>
#include <vector>

#include "core/types.h"
#include "hierarchy/element_tree.h"
#include "patch/patch_set.h"
#include "visibility/visibility.h"

namespace radwalk {

struct HierarchicalOptions {
  double tol = 1e-3;       // epsilon = tol * Phi_E (> 0)
  double min_area = 0;     // no element below this area (0: max_level alone bounds the depth)
  int max_level = 8;       // deepest level (a root is level 0)
  int points_side = 4;     // m: m^2 points per element for the direct light (direct_refinement.h)
  long particles = 1'000'000;  // rays of the indirect shooting, all replicates and iterations together
  int replicates = 4;      // R >= 2
  std::uint64_t seed = 1;
  std::uint64_t direct_seed = 0;  // the direct light's points and shadow rays from this seed (0: from seed); a bench
                                  // gives runs of different seeds one D so that their indirect light compares alone
  bool progress = false;
  // The a-priori oracles. direct_oracle false: the direct light is estimated on the starting leaves and nothing is
  // split for it. transport_oracle false: every ray's power is gathered at the leaf containing its end point (the
  // leaves act as patches, as the ordinary stochastic Jacobi's: unbiased for the leaves' discrete system) and no
  // element is split during the shooting. Both off: the tree is the one given (estimate_refinement.h splits it).
  bool direct_oracle = true;
  bool transport_oracle = true;
  // Oriented clusters of patches above the element trees (cluster_tree.h): a ray's incident power is received by
  // the coarsest cluster containing the hit patch that passes cluster_receives(ratio = cluster_ratio) from the
  // shooter leaf's centre, and spread over its members by the cosine rule; else the element oracle above decides.
  bool clusters = false;
  double cluster_ratio = 0.25;  // a cluster receives only where its radius <= cluster_ratio x its distance
  int cluster_leaf_size = 8;    // patches per leaf cluster at most (>= 2)
};

struct HierarchicalResult {
  ElementTree tree;
  std::vector<ElementIndex> leaves;  // the output order: leaf k is row k of B
  PatchRgb B, B_se, var, D;          // per leaf; var: the replicates' variance x rays (as the walk solvers report)
  double epsilon = 0;
  long rays = 0, shadow_rays = 0, iterations = 0;
  long direct_splits = 0, transport_splits = 0;
  std::size_t clusters = 0;   // cluster nodes (0 without clustering)
  long cluster_deposits = 0;  // rays received by a cluster rather than an element
  std::size_t memory_bytes = 0;  // the trees (elements and clusters) and their arrays at their largest
  double seconds = 0;
};

// Whether the options' depth bounds allow children below element e: e above max_level and its quarters of at least
// min_area. The oracles descend, and every refinement splits, only where this holds.
bool within_depth(const ElementTree& tree, std::size_t e, const HierarchicalOptions& options);

// Whether element e may be split now: a leaf within_depth.
bool splittable(const ElementTree& tree, std::size_t e, const HierarchicalOptions& options);

// roots: the input patches (their tree is made here); visibility over roots. Throws InputError on options out of
// range (tol <= 0 or not finite, replicates < 2, particles < 1, max_level < 0, points_side < 1).
HierarchicalResult solve_hierarchical(const PatchSet& roots, const Visibility& visibility,
                                      const HierarchicalOptions& options);

// The same from a given starting tree over `roots` (its leaves are where the direct light is first estimated and
// the shooting starts; the oracles may split it further).
HierarchicalResult solve_hierarchical(const PatchSet& roots, const Visibility& visibility, ElementTree start,
                                      const HierarchicalOptions& options);

}  // namespace radwalk
