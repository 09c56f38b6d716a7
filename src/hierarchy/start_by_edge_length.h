#pragma once
// The start of `--hierarchical --target-error` given no patching (no --max-edge or --max-area; Python: a Scene
// loaded without them): each input face's element tree (root) split by edge length until the roots and about
// `more` leaves more cover the scene.
//
// Rounds of splitting every element longer than L (a quad's larger extent, a triangle's longest edge), L the
// largest length whose elements number at least roots + more, found by bisection in log L over [1e-4, 1] x the
// longest root (30 halvings: L to a relative 1e-4, far finer than the count's steps). With bands, a quad longer
// than L one way only and more than twice as long as wide is cut in bands across its length (bands at most twice as
// long as wide), as uniform patching by edge length cuts a strip; else it is cut in quarters. A round that would
// pass the budget (3 more elements per split) is not made.
//
// Why by edge length and relative to the roots: a start of 500 by area in quarters put 64 elements on each wall of
// the Cornell box and few on its blocks, and measured a discretisation error of 1.1-1.2 % with 607 patches, where
// this start measures about 1 % with 286 (docs/accuracy.md), and on the spot-lit room the hierarchy stopped once
// at 1.22 x its estimate from it; a fixed count below the input faces (the furniture
// room's 341) would leave its large faces whole (docs/hierarchy.md, "A start by edge length").
#include <cstddef>

#include "hierarchy/element_tree.h"
#include "hierarchy/hierarchical_jacobi.h"
#include "patch/patch_set.h"

namespace radwalk {

// `more` of the default start: the roots and about 200 elements more.
inline constexpr std::size_t kStartMoreElements = 200;

// The element trees of `roots` split as above (more = 0: unsplit), within max_leaves and the options' depth.
ElementTree start_by_edge_length(const PatchSet& roots, std::size_t more, long max_leaves, bool bands,
                                 const HierarchicalOptions& solve);

}  // namespace radwalk
