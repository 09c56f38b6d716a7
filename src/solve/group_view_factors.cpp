#include "solve/group_view_factors.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"

namespace radwalk {

GroupViewFactors group_view_factors(const SparseF& F, const std::vector<double>& area,
                                    const std::vector<std::int32_t>& group, int groups, const std::vector<double>& sky,
                                    const std::vector<double>& back) {
  const std::size_t n = area.size();
  RADWALK_CHECK_EQ(group.size(), n);
  RADWALK_CHECK_EQ(static_cast<std::size_t>(F.rows()), n);
  GroupViewFactors g;
  g.area.assign(std::size_t(groups), 0.0);
  g.sky.assign(std::size_t(groups), 0.0);
  g.back.assign(std::size_t(groups), 0.0);
  g.F = Eigen::MatrixXd::Zero(groups, groups);  // first the exchange areas A_G F_GH
  for (std::size_t i = 0; i < n; ++i) {
    const std::int32_t G = group[i];
    RADWALK_CHECK(G >= 0 && G < groups);
    g.area[std::size_t(G)] += area[i];
    if (!sky.empty()) g.sky[std::size_t(G)] += area[i] * sky[i];
    if (!back.empty()) g.back[std::size_t(G)] += area[i] * back[i];
    for (SparseF::InnerIterator it(F, static_cast<Eigen::Index>(i)); it; ++it)
      g.F(G, group[static_cast<std::size_t>(it.col())]) += area[i] * double(it.value());
  }
  for (int G = 0; G < groups; ++G) {
    const double A = g.area[std::size_t(G)];
    if (!(A > 0)) continue;
    g.F.row(G) /= A;
    g.sky[std::size_t(G)] /= A;
    g.back[std::size_t(G)] /= A;
  }
  return g;
}

double group_reciprocity_defect(const GroupViewFactors& g) {
  double worst = 0;
  const auto m = g.F.rows();
  for (Eigen::Index a = 0; a < m; ++a)
    for (Eigen::Index b = a + 1; b < m; ++b) {
      const double x = g.area[std::size_t(a)] * g.F(a, b), y = g.area[std::size_t(b)] * g.F(b, a);
      const double size = std::max(x, y);
      if (size > 0) worst = std::max(worst, std::abs(x - y) / size);
    }
  return worst;
}

}  // namespace radwalk
