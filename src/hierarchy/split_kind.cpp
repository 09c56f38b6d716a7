#include "hierarchy/split_kind.h"

#include <algorithm>
#include <utility>

namespace radwalk {

std::pair<double, double> quad_extents(const ElementTree& tree, std::size_t e) {
  if (tree.corner_count[e] != 4) return {0.0, 0.0};
  const auto& c = tree.corner[e];
  return {0.5 * ((c[1] - c[0]).norm() + (c[2] - c[3]).norm()), 0.5 * ((c[3] - c[0]).norm() + (c[2] - c[1]).norm())};
}

SplitKind choose_split_kind(const ElementTree& tree, std::size_t e, double along_01, double along_03,
                            const SplitKindRule& rule) {
  if (tree.corner_count[e] != 4) return SplitKind::regular;
  const auto [L01, L03] = quad_extents(tree, e);
  if (!(L01 > 0 && L03 > 0)) return SplitKind::regular;
  // Children of bands_01 are L_01 / 4 by L_03; of bands_12, L_01 by L_03 / 4.
  const bool can01 = L03 <= rule.max_child_aspect * L01 / 4, can03 = L01 <= rule.max_child_aspect * L03 / 4;
  const double V01 = std::max(along_01, 0.0), V03 = std::max(along_03, 0.0);
  if (V01 + V03 > 0) {
    SplitKind best = SplitKind::regular;
    double least = (V01 + V03) / 4;
    if (can01 && V01 / 16 + V03 < least) {
      least = V01 / 16 + V03;
      best = SplitKind::bands_01;
    }
    if (can03 && V01 + V03 / 16 < least) best = SplitKind::bands_12;
    return best;
  }
  if (can01 && L01 > rule.shape_ratio * L03) return SplitKind::bands_01;
  if (can03 && L03 > rule.shape_ratio * L01) return SplitKind::bands_12;
  return SplitKind::regular;
}

}  // namespace radwalk
