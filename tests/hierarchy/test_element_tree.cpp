// The element tree and push-pull (hierarchy/element_tree.h, push_pull.h, leaf_patches.h): children tile their parent
// exactly (areas add up, corners in the parent's plane, every point of the parent in the child chosen for it),
// push and pull conserve power exactly (up to rounding), and the leaves as a PatchSet keep their input faces.
// Deterministic properties: exact up to a stated rounding bound, no statistics.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/rng.h"
#include "hierarchy/element_tree.h"
#include "hierarchy/leaf_patches.h"
#include "hierarchy/push_pull.h"
#include "patch/patch_builder.h"

using namespace radwalk;

namespace {

// A planar convex quad (not a parallelogram) and a scalene triangle, in a tilted plane.
PatchSet two_faces() {
  PatchBuilder b;
  const int m = b.add_material("grey", Rgb(0.5, 0.4, 0.3), Rgb(0.1, 0, 0));
  const Vec3 o(0.3, -0.2, 0.7), u = Vec3(1, 0.2, 0.1).normalized(), v0 = Vec3(-0.1, 1, 0.3);
  const Vec3 v = (v0 - v0.dot(u) * u).normalized();
  const auto at = [&](double a, double c) { return Vec3(o + a * u + c * v); };
  b.add_quad(at(0, 0), at(2, 0.1), at(1.7, 1.3), at(0.2, 0.9), m);
  b.add_triangle(at(3, 0), at(4.5, 0.3), at(3.4, 2.1), m);
  return b.build();
}

// Splits random leaves of `tree` until it has at least `elements` elements.
void grow(ElementTree& tree, std::size_t elements, std::uint64_t seed) {
  Rng rng = stream(seed, StreamDomain::test, 11, 0);
  while (tree.size() < elements) {
    const std::vector<ElementIndex> leaves = tree.leaves();
    tree.split(static_cast<std::size_t>(leaves[rng.uniform_index(static_cast<std::uint32_t>(leaves.size()))]));
  }
}

}  // namespace

TEST_CASE("element tree: the four children tile their parent (areas, plane, point location)", "[hierarchy]") {
  const PatchSet patches = two_faces();
  ElementTree tree = make_element_tree(patches);
  grow(tree, 400, 1);
  Rng rng = stream(2, StreamDomain::test, 12, 0);
  for (std::size_t e = 0; e < tree.size(); ++e) {
    if (tree.is_leaf(e)) continue;
    const Vec3& n = patches.normal[static_cast<std::size_t>(tree.root[e])];
    double sum = 0;
    for (ElementIndex c = tree.first_child[e]; c < tree.first_child[e] + 4; ++c) {
      sum += tree.area[static_cast<std::size_t>(c)];
      CHECK(tree.level[static_cast<std::size_t>(c)] == tree.level[e] + 1);
      for (int k = 0; k < tree.corner_count[static_cast<std::size_t>(c)]; ++k)
        CHECK(std::abs((tree.corner[static_cast<std::size_t>(c)][static_cast<std::size_t>(k)] - tree.corner[e][0]).dot(n)) <=
              1e-12);
    }
    // Rounding of a few operations on coordinates of order 1: 1e-13 relative is far above it.
    CHECK(std::abs(sum - tree.area[e]) <= 1e-13 * tree.area[e] + 1e-15);
    // Uniform points of the parent: the chosen child contains each (signed distance to its edges >= -1e-12).
    for (int s = 0; s < 20; ++s) {
      const Vec3 p = element_point(tree, e, rng.uniform(), rng.uniform());
      const auto c = static_cast<std::size_t>(tree.child_containing(e, p, n));
      const int k = tree.corner_count[c];
      double inside = 1e300;
      for (int a = 0; a < k; ++a) {
        const Vec3& p0 = tree.corner[c][static_cast<std::size_t>(a)];
        const Vec3& p1 = tree.corner[c][static_cast<std::size_t>((a + 1) % k)];
        inside = std::min(inside, (p1 - p0).cross(p - p0).dot(n) / (p1 - p0).norm());
      }
      CHECK(inside >= -1e-12);
    }
  }
  // The fraction of uniform points of a root that each child gets is its share of the area (a chi-square would
  // test the sampler; the geometric checks above already pin the tiling, so here only the leaves' total).
  double leaf_area = 0;
  for (const ElementIndex l : tree.leaves()) leaf_area += tree.area[static_cast<std::size_t>(l)];
  CHECK(std::abs(leaf_area - patches.total_area()) <= 1e-12 * patches.total_area());
}

TEST_CASE("push-pull: pushing gathered radiosity and pulling leaf radiosity conserve power exactly", "[hierarchy]") {
  const PatchSet patches = two_faces();
  ElementTree tree = make_element_tree(patches);
  grow(tree, 1000, 3);
  Rng rng = stream(4, StreamDomain::test, 13, 0);
  std::vector<Rgb> gathered(tree.size());
  for (Rgb& g : gathered) g = Rgb(rng.uniform(), rng.uniform(), 10 * rng.uniform());
  const Rgb before = power(tree, gathered, false);
  std::vector<Rgb> pushed = gathered;
  push(tree, pushed);
  const Rgb after = power(tree, pushed, true);
  for (int c = 0; c < 3; ++c) CHECK(std::abs(after[c] - before[c]) <= 1e-12 * before[c]);
  // A deliberately wrong push (children get half their parent's value) loses power: the check can fail.
  std::vector<Rgb> wrong = gathered;
  for (std::size_t e = 0; e < tree.size(); ++e)
    if (tree.parent[e] >= 0) wrong[e] += 0.5 * wrong[static_cast<std::size_t>(tree.parent[e])];
  CHECK(std::abs(power(tree, wrong, true)[0] - before[0]) > 1e-3 * before[0]);

  std::vector<Rgb> pulled = pushed;
  pull(tree, pulled);
  for (std::size_t e = 0; e < tree.size(); ++e) {
    if (tree.parent[e] >= 0) continue;
    Rgb leaves = Rgb::Zero();
    for (const ElementIndex l : tree.leaves())
      if (tree.root[static_cast<std::size_t>(l)] == tree.root[e])
        leaves += tree.area[static_cast<std::size_t>(l)] * pushed[static_cast<std::size_t>(l)];
    for (int c = 0; c < 3; ++c)
      CHECK(std::abs(tree.area[e] * pulled[e][c] - leaves[c]) <= 1e-12 * leaves[c]);
  }
}

TEST_CASE("leaf patches: every leaf keeps its input face, material and radiometry, and the areas add up", "[hierarchy]") {
  const PatchSet patches = two_faces();
  ElementTree tree = make_element_tree(patches);
  grow(tree, 200, 5);
  const std::vector<ElementIndex> leaves = tree.leaves();
  const PatchSet p = leaf_patches(patches, tree, leaves);
  REQUIRE(p.size() == leaves.size());
  std::vector<double> area(patches.size(), 0.0);
  for (std::size_t k = 0; k < p.size(); ++k) {
    const auto r = static_cast<std::size_t>(tree.root[static_cast<std::size_t>(leaves[k])]);
    CHECK(p.face[k] == patches.face[r]);
    CHECK(p.material[k] == patches.material[r]);
    CHECK((p.rho[k] == patches.rho[r]).all());
    CHECK((p.E[k] == patches.E[r]).all());
    CHECK(p.normal[k].dot(patches.normal[r]) > 1 - 1e-12);
    area[r] += p.area[k];
  }
  for (std::size_t r = 0; r < patches.size(); ++r) CHECK(std::abs(area[r] - patches.area[r]) <= 1e-12 * patches.area[r]);
  // Shared corners are welded: fewer points than 4 per leaf.
  CHECK(p.points.size() < 3 * p.size());
}
