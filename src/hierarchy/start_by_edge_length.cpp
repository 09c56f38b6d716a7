#include "hierarchy/start_by_edge_length.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "hierarchy/split_kind.h"

namespace radwalk {
namespace {

// The longest side of element e: a quad's larger extent (split_kind.h, quad_extents), a triangle's longest edge.
double longest_extent(const ElementTree& tree, std::size_t e) {
  if (tree.corner_count[e] == 4) {
    const auto [L01, L03] = quad_extents(tree, e);
    return std::max(L01, L03);
  }
  const auto& c = tree.corner[e];
  return std::max({(c[1] - c[0]).norm(), (c[2] - c[1]).norm(), (c[0] - c[2]).norm()});
}

// Rounds of splitting every leaf longer than L (header), each only if the leaves stay within max_leaves.
// tree: the unsplit trees of the roots (a copy, split here).
ElementTree split_to_extent(ElementTree tree, const HierarchicalOptions& solve, long max_leaves, double L, bool bands) {
  for (;;) {
    const std::vector<ElementIndex> leaves = tree.leaves();
    std::vector<ElementIndex> marked;
    for (const ElementIndex e : leaves) {
      const auto x = static_cast<std::size_t>(e);
      if (longest_extent(tree, x) > L && splittable(tree, x, solve)) marked.push_back(e);
    }
    if (marked.empty() || static_cast<long>(leaves.size() + 3 * marked.size()) > max_leaves) return tree;
    for (const ElementIndex e : marked) {
      const auto x = static_cast<std::size_t>(e);
      SplitKind kind = SplitKind::regular;
      if (bands && tree.corner_count[x] == 4) {
        const auto [L01, L03] = quad_extents(tree, x);
        if (L03 <= L && L01 > 2 * L03) kind = SplitKind::bands_01;
        if (L01 <= L && L03 > 2 * L01) kind = SplitKind::bands_12;
      }
      tree.split(x, kind);
    }
  }
}

}  // namespace

ElementTree start_by_edge_length(const PatchSet& roots, std::size_t more, long max_leaves, bool bands,
                                 const HierarchicalOptions& solve) {
  const ElementTree unsplit = make_element_tree(roots);
  if (more == 0) return unsplit;
  const std::size_t wanted = roots.size() + more;
  double longest = 0;
  for (const ElementIndex e : unsplit.leaves()) longest = std::max(longest, longest_extent(unsplit, std::size_t(e)));
  double lo = 1e-4 * longest, hi = longest;
  for (int it = 0; it < 30; ++it) {
    const double mid = std::sqrt(lo * hi);
    (split_to_extent(unsplit, solve, max_leaves, mid, bands).leaves().size() >= wanted ? lo : hi) = mid;
  }
  return split_to_extent(unsplit, solve, max_leaves, lo, bands);
}

}  // namespace radwalk
