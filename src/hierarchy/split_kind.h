#pragma once
// Which split a leaf gets (element_tree.h: regular, or bands across one edge pair of a quad), from its shape and,
// where estimated, from the direction in which the radiosity varies inside it (docs/theory/hierarchical_radiosity.md,
// "Band splits").
//
// Model: inside a quad leaf the radiosity is g(u, v) = a(u) + b(v) + (smaller terms), u along c0 -> c1 of extent
// L_01 = (|c1 - c0| + |c2 - c3|) / 2, v along c0 -> c3 of extent L_03 = (|c3 - c0| + |c2 - c1|) / 2, with variances
// V_01 = Var(a), V_03 = Var(b) over the leaf (leaf_variation.h, leaf_directional_variation). A split that divides
// the extent along a direction by s divides a linear variation's variance along it by s^2, so the mean within-child
// variance after each split is
//   regular  (V_01 + V_03) / 4,    bands_01  V_01 / 16 + V_03,    bands_03 (SplitKind::bands_12)  V_01 + V_03 / 16,
// and the rule takes the smallest (regular on ties), among the kinds whose children's aspect stays at most
// max_child_aspect (the children of bands_01 measure L_01 / 4 by L_03). Where the estimate is missing or shows no
// variation (V_01, V_03 <= 0, clamped), the prior of an isotropic gradient (V proportional to L^2) is used, but only
// for a clear shape: a quad whose extent along one direction is more than shape_ratio times the other's is cut in
// bands across that direction (a 23:1 strip -> four of about 6:1 -> regular or bands again), else regular. A noisy
// V that picks the wrong bands costs one split that is no better than a regular one along the other direction; the
// children's aspect bound keeps such mistakes from making slivers. Triangles: always regular (element_tree.h).
#include <cstddef>
#include <utility>

#include "hierarchy/element_tree.h"

namespace radwalk {

struct SplitKindRule {
  double shape_ratio = 3;        // bands by shape alone beyond this aspect
  double max_child_aspect = 16;  // no split whose children are longer than this times their width
};

// L_01 and L_03 above of element e (a quad; for a triangle both are 0).
std::pair<double, double> quad_extents(const ElementTree& tree, std::size_t e);

// The split of leaf e by the rule above; along_01, along_03: V_01, V_03 (any sign; pass 0, 0 where not estimated).
SplitKind choose_split_kind(const ElementTree& tree, std::size_t e, double along_01, double along_03,
                            const SplitKindRule& rule = {});

}  // namespace radwalk
