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

// The same variation split by direction on a quad leaf (docs/theory/hierarchical_radiosity.md, "Band splits"): the
// M = m^2 points lie on the leaf's parametric grid, y_ij = the bilinear point of u = (i + xi) / m along c0 -> c1 and
// v = (j + xi') / m along c0 -> c3 (i, j = 0 .. m-1, xi uniform jitter; a bilinear map, uniform in area on a
// parallelogram). With gbar_q.j (the column mean of replicate q: over j at fixed i) and gbar_q.i. (the row mean),
//   along_01 = sum_c rho_c^2 sum_i (gbar_0i. - gbar_0..)(gbar_1i. - gbar_1..) / (m - 1)   (the column means vary
//              along c0 -> c1),
//   along_03 = the same with the row means (vary along c0 -> c3),
// the cross-replicate covariances of the two-way ANOVA's main effects: unbiased for the variance of the exact g's
// column (row) means, times rho^2, with no noise term (the header's argument); summed over the channels. For
// g(u, v) = a(u) + b(v), along_01 estimates Var(a) and along_03 Var(b); a linear variation of extent L along a
// direction has variance proportional to L^2. Either may be < 0 where it is below the noise. elements: the leaves
// to estimate (a subset of `leaves`, whose solution B is); a triangle gets 0, 0. Rays per quad: 2 m^2 (L + number
// of emitters). Streams as leaf_variation's (the same points' stream, laid out on the grid).
struct DirectionalVariation {
  std::vector<double> along_01, along_03;  // per element of `elements`
  long rays = 0;
};

DirectionalVariation leaf_directional_variation(const PatchSet& roots, const Visibility& visibility,
                                                const ElementTree& tree, const std::vector<ElementIndex>& leaves,
                                                const PatchRgb& B, const std::vector<ElementIndex>& elements,
                                                int points_side, int directions, std::uint64_t seed);

// The bilinear point (1 - v) ((1 - u) c0 + u c1) + v ((1 - u) c3 + u c2) of quad element e, (u, v) in [0, 1]^2.
Vec3 element_bilinear_point(const ElementTree& tree, std::size_t e, double u, double v);

}  // namespace radwalk
