#pragma once
// The radiosity's variation inside each leaf element, the part of the error of a piecewise-constant solution that
// the error of the leaf's average (B_disc) does not hold (docs/theory/hierarchical_radiosity.md, "Refinement by the
// estimate").
//
// With the one-gather model of the discretisation estimate (docs/theory/discretisation_error.md, (4)),
//   B(y) - Bbar_l ~ rho_l (g(y) - gbar_l),
//   g(y) = sum_k E_k [F(y -> k) - A_k G(y, z_k) (1 - V(y, z_k))] + int (B_h - E)(hit(y, w)) cos / pi dw,
// F(y -> k) Lambert's exact unoccluded point-to-polygon factor of emitter k, z_k a uniform point of k (the
// unbiased visible factor of direct_refinement.h, visible_point_form_factor), B_h the leaves' solution. At M = m^2 stratified jittered points y_s of leaf l (the same points for both replicates), two
// independent replicates q = 0, 1 of g, each with L cosine directions and one point z_k per emitter shared by the M
// points (common random numbers: where the points see the same thing their g agree exactly), give
//   W2_lc = rho_c^2 sum_s (g0_sc - mean_s g0_c)(g1_sc - mean_s g1_c) / (M - 1),
// the cross-replicate covariance: the two replicates' noises are independent and zero-mean given the points, so
// E[W2] is rho^2 times the sample variance of the exact g over the points, with no noise term (the noise of one
// replicate's own sample variance would add Var(g_s - mean g) to it). W2 can be negative where the variation is
// below the noise; the caller clamps. (1/A_l) int_l (B - Bbar_l)^2 ~ W2 up to the stratification of the points.
// Rays per leaf: 2 M (L + number of emitters). Reproducible: leaf element e draws its points from stream
// (seed, hierarchical_variation, e, 0) and replicate q's directions and emitter points from (.., e, 1 + q); leaves
// in parallel, each result its own.
#include <cstdint>
#include <vector>

#include "core/types.h"
#include "hierarchy/element_tree.h"
#include "patch/patch_set.h"
#include "visibility/visibility.h"

namespace radwalk {

struct LeafVariation {
  PatchRgb W2;    // per leaf (row k = leaves[k]): the estimate above, per channel (may be < 0)
  long rays = 0;
};

// roots: the PatchSet the tree was made from; visibility over roots; B: the leaves' solution (row k = leaves[k],
// finite). points_side m >= 2, directions L >= 1.
LeafVariation leaf_variation(const PatchSet& roots, const Visibility& visibility, const ElementTree& tree,
                             const std::vector<ElementIndex>& leaves, const PatchRgb& B, int points_side,
                             int directions, std::uint64_t seed);

}  // namespace radwalk
