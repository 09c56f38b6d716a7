// The split kind of a leaf (hierarchy/split_kind.h) and the directional variation it reads
// (hierarchy/leaf_variation.h, leaf_directional_variation):
//   - shape: a quad more than 3 times longer than wide, with no estimate, is cut in bands across its length; a
//     square is split regularly; the children's aspect bound forbids bands that would make slivers; the variance
//     model's break-even (bands_01 once V_01 > 4 V_03) is where the rule switches;
//   - direction: a floor lit by a long line-like light along one wall (light and wall 5 times longer than the floor,
//     so the floor's radiosity varies across the wall and hardly along it) cut into 64 square leaves. Each leaf's
//     estimate uses its own streams, so the leaves are independent; if the indicator did not tell the two directions
//     apart, each leaf would pick the bands across the wall with probability at most 1/2. Sign test, alpha = 1e-3
//     one-sided: the count of leaves choosing those bands must reach the smallest k with P(Bin(64, 1/2) >= k) <=
//     1e-3 (k = 45). The same floor with its corners listed from another corner (c0 -> c1 along the wall) must
//     choose the other kind as often (a grid laid out the wrong way round fails one of the two).
#include <catch2/catch.hpp>

#include <cmath>

#include "hierarchy/leaf_variation.h"
#include "hierarchy/split_kind.h"
#include "patch/patch_builder.h"
#include "visibility/embree_visibility.h"

using namespace radwalk;

namespace {

PatchSet one_quad(double length, double width) {
  PatchBuilder b;
  const int m = b.add_material("grey", Rgb::Constant(0.5));
  b.add_quad(Vec3(0, 0, 0), Vec3(length, 0, 0), Vec3(length, width, 0), Vec3(0, width, 0), m);
  return b.build();
}

// The floor [0, 1]^2 (z = 0, up; c0 -> c1 along x, or along y when `turned`), a wall x = 0 (y in [-2, 3], z in
// [0, 1], rho 0.5) and a light strip under the wall's foot (x in [0.01, 0.05], y in [-2, 3], z = 0.05, facing
// down).
PatchSet line_lit_floor(bool turned) {
  PatchBuilder b;
  const int floor = b.add_material("floor", Rgb::Constant(0.6));
  const int wall = b.add_material("wall", Rgb::Constant(0.5));
  const int light = b.add_material("light", Rgb::Zero(), Rgb::Constant(5.0));
  if (turned)
    b.add_quad(Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), Vec3(0, 0, 0), floor);
  else
    b.add_quad(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), floor);
  b.add_quad(Vec3(0, -2, 0), Vec3(0, 3, 0), Vec3(0, 3, 1), Vec3(0, -2, 1), wall);
  b.add_quad(Vec3(0.01, -2, 0.05), Vec3(0.01, 3, 0.05), Vec3(0.05, 3, 0.05), Vec3(0.05, -2, 0.05), light);
  return b.build();
}

// P(Bin(n, 1/2) >= k).
double binomial_half_upper(int n, int k) {
  double p = 0;
  for (int j = k; j <= n; ++j)
    p += std::exp(std::lgamma(n + 1) - std::lgamma(j + 1) - std::lgamma(n - j + 1) - n * std::log(2.0));
  return p;
}

}  // namespace

TEST_CASE("split kind: long quads in bands across their length and squares regular without an estimate", "[hierarchy]") {
  const auto kind_of = [](double length, double width, double v01, double v03) {
    const PatchSet p = one_quad(length, width);
    const ElementTree t = make_element_tree(p);
    return choose_split_kind(t, 0, v01, v03);
  };
  CHECK(kind_of(23, 1, 0, 0) == SplitKind::bands_01);
  CHECK(kind_of(1, 23, 0, 0) == SplitKind::bands_12);
  CHECK(kind_of(1, 1, 0, 0) == SplitKind::regular);
  CHECK(kind_of(2.9, 1, 0, 0) == SplitKind::regular);
  CHECK(kind_of(3.1, 1, -1, -2) == SplitKind::bands_01);  // negative (noise) estimates count as none
  // The variance model: bands_01 beats regular once V_01 > 4 V_03.
  CHECK(kind_of(1, 1, 4.1, 1) == SplitKind::bands_01);
  CHECK(kind_of(1, 1, 3.9, 1) == SplitKind::regular);
  CHECK(kind_of(1, 1, 1, 4.1) == SplitKind::bands_12);
  // A strip 23:1 varying across its width would give 92:1 bands: bounded by the children's aspect (16), regular
  // wins; varying along its length, bands across it.
  CHECK(kind_of(23, 1, 0, 1) == SplitKind::regular);
  CHECK(kind_of(23, 1, 1, 0) == SplitKind::bands_01);
  // A 4:1 element still varying across its short side: bands to 16:1 allowed, not beyond.
  CHECK(kind_of(1, 4, 1, 0) == SplitKind::bands_01);
  CHECK(kind_of(1, 4.5, 1, 0) == SplitKind::regular);
  // Triangles: regular.
  PatchBuilder b;
  const int m = b.add_material("grey", Rgb::Constant(0.5));
  b.add_triangle(Vec3(0, 0, 0), Vec3(23, 0, 0), Vec3(0, 1, 0), m);
  const PatchSet tri = b.build();
  CHECK(choose_split_kind(make_element_tree(tri), 0, 1, 0) == SplitKind::regular);
}

TEST_CASE("split kind: a floor lit along one wall is cut in bands across the wall (sign test)", "[hierarchy]") {
  const int n = 64;
  int k = 0;
  while (binomial_half_upper(n, k) > 1e-3) ++k;
  REQUIRE(k == 45);
  for (const bool turned : {false, true}) {
    const PatchSet roots = line_lit_floor(turned);
    const EmbreeVisibility visibility(roots);
    ElementTree tree = make_element_tree(roots);
    // The floor (root 0) in 64 squares: three levels of regular splits.
    for (int level = 0; level < 3; ++level)
      for (const ElementIndex l : tree.leaves())
        if (tree.root[static_cast<std::size_t>(l)] == 0) tree.split(static_cast<std::size_t>(l));
    const std::vector<ElementIndex> leaves = tree.leaves();
    PatchRgb B = PatchRgb::Zero(static_cast<Eigen::Index>(leaves.size()), 3);
    std::vector<ElementIndex> floor;
    for (std::size_t i = 0; i < leaves.size(); ++i) {
      const auto r = static_cast<std::size_t>(tree.root[static_cast<std::size_t>(leaves[i])]);
      // A made-up solution: the light emits only, the wall a constant 0.5 (it shoots a noisy constant), the floor 0.
      const Rgb value = r == 2 ? roots.E[r] : (r == 1 ? Rgb(Rgb::Constant(0.5)) : Rgb(Rgb::Zero()));
      B.row(static_cast<Eigen::Index>(i)) = value.transpose();
      if (r == 0) floor.push_back(leaves[i]);
    }
    REQUIRE(floor.size() == static_cast<std::size_t>(n));
    const DirectionalVariation d = leaf_directional_variation(roots, visibility, tree, leaves, B, floor, 4, 16, 17);
    const SplitKind across = turned ? SplitKind::bands_12 : SplitKind::bands_01;
    int chose = 0;
    for (std::size_t i = 0; i < floor.size(); ++i)
      chose += choose_split_kind(tree, static_cast<std::size_t>(floor[i]), d.along_01[i], d.along_03[i]) == across;
    INFO("turned " << turned << ": " << chose << " of " << n << " leaves chose the bands across the wall (need " << k
                   << "); first leaf V_01 " << d.along_01[0] << ", V_03 " << d.along_03[0]);
    CHECK(chose >= k);
    CHECK(d.rays >= n * 2L * 16 * 16);  // at least the directions' rays
  }
}
