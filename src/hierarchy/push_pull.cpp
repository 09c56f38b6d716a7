#include "hierarchy/push_pull.h"

#include "core/check.h"

namespace radwalk {

void push(const ElementTree& tree, std::vector<Rgb>& values) {
  RADWALK_CHECK_EQ(values.size(), tree.size());
  for (std::size_t e = 0; e < tree.size(); ++e)
    if (tree.parent[e] >= 0) values[e] += values[static_cast<std::size_t>(tree.parent[e])];
}

void pull(const ElementTree& tree, std::vector<Rgb>& values) {
  RADWALK_CHECK_EQ(values.size(), tree.size());
  for (std::size_t k = tree.size(); k-- > 0;) {
    const ElementIndex c = tree.first_child[k];
    if (c < 0) continue;
    Rgb sum = Rgb::Zero();
    double area = 0;
    for (ElementIndex q = c; q < c + 4; ++q) {
      sum += tree.area[static_cast<std::size_t>(q)] * values[static_cast<std::size_t>(q)];
      area += tree.area[static_cast<std::size_t>(q)];
    }
    values[k] = area > 0 ? Rgb(sum / area) : Rgb(Rgb::Zero());
  }
}

Rgb power(const ElementTree& tree, const std::vector<Rgb>& values, bool leaves_only) {
  RADWALK_CHECK_EQ(values.size(), tree.size());
  Rgb p = Rgb::Zero();
  for (std::size_t e = 0; e < tree.size(); ++e)
    if (!leaves_only || tree.is_leaf(e)) p += tree.area[e] * values[e];
  return p;
}

}  // namespace radwalk
