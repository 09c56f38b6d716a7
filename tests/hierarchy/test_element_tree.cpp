// The element tree and push-pull (hierarchy/element_tree.h, push_pull.h, leaf_patches.h): children tile their parent
// exactly (areas add up, corners in the parent's plane, every point of the parent in the child chosen for it),
// push and pull conserve power exactly (up to rounding), and the leaves as a PatchSet keep their input faces.
// Deterministic properties: exact up to a stated rounding bound, no statistics.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
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

// Splits random leaves of `tree` until it has at least `elements` elements; with `bands`, each quad's split kind
// is drawn among regular, bands_01 and bands_12.
void grow(ElementTree& tree, std::size_t elements, std::uint64_t seed, bool bands = false) {
  Rng rng = stream(seed, StreamDomain::test, 11, 0);
  while (tree.size() < elements) {
    std::vector<ElementIndex> leaves = tree.leaves();
    // With bands, mostly the quad's leaves (the triangle's leaves would soon outnumber them).
    if (bands && rng.uniform() < 0.7)
      leaves.erase(std::remove_if(leaves.begin(), leaves.end(),
                                  [&](ElementIndex l) { return tree.corner_count[static_cast<std::size_t>(l)] != 4; }),
                   leaves.end());
    const auto e = static_cast<std::size_t>(leaves[rng.uniform_index(static_cast<std::uint32_t>(leaves.size()))]);
    SplitKind kind = SplitKind::regular;
    if (bands && tree.corner_count[e] == 4) {
      const std::uint32_t draw = rng.uniform_index(3);
      kind = draw == 1 ? SplitKind::bands_01 : (draw == 2 ? SplitKind::bands_12 : SplitKind::regular);
    }
    tree.split(e, kind);
  }
}

// The children of every split element tile it: areas add up, corners in its plane, and every uniform point of it
// lies in the child that child_containing picks.
void check_tiling(const PatchSet& patches, const ElementTree& tree) {
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
      // No other child holds it beyond rounding: the children's interiors are disjoint.
      int holders = 0;
      for (ElementIndex q = tree.first_child[e]; q < tree.first_child[e] + 4; ++q) {
        const auto& cq = tree.corner[static_cast<std::size_t>(q)];
        const int kq = tree.corner_count[static_cast<std::size_t>(q)];
        double in_q = 1e300;
        for (int a = 0; a < kq; ++a) {
          const Vec3& p0 = cq[static_cast<std::size_t>(a)];
          const Vec3& p1 = cq[static_cast<std::size_t>((a + 1) % kq)];
          in_q = std::min(in_q, (p1 - p0).cross(p - p0).dot(n) / (p1 - p0).norm());
        }
        holders += in_q > 1e-12;
      }
      CHECK(holders <= 1);
    }
  }
  // The fraction of uniform points of a root that each child gets is its share of the area (a chi-square would
  // test the sampler; the geometric checks above already pin the tiling, so here only the leaves' total).
  double leaf_area = 0;
  for (const ElementIndex l : tree.leaves()) leaf_area += tree.area[static_cast<std::size_t>(l)];
  CHECK(std::abs(leaf_area - patches.total_area()) <= 1e-12 * patches.total_area());
}

}  // namespace

TEST_CASE("element tree: the four children tile their parent (areas, plane, point location)", "[hierarchy]") {
  const PatchSet patches = two_faces();
  ElementTree tree = make_element_tree(patches);
  grow(tree, 400, 1);
  check_tiling(patches, tree);
}

TEST_CASE("element tree: band splits tile their parent and are four times thinner across the cuts", "[hierarchy]") {
  const PatchSet patches = two_faces();
  ElementTree tree = make_element_tree(patches);
  grow(tree, 600, 21, true);
  long bands = 0;
  for (std::size_t e = 0; e < tree.size(); ++e) bands += tree.split_kind[e] != SplitKind::regular;
  long quads_split = 0;
  for (std::size_t e = 0; e < tree.size(); ++e) quads_split += !tree.is_leaf(e) && tree.corner_count[e] == 4;
  INFO("band splits " << bands << " of " << quads_split << " quad splits; kinds " << tree.split_kind.size());
  REQUIRE(bands > 20);
  check_tiling(patches, tree);
  // A band child's corners: two on the edge c0 c1 (bands_01) at t = q/4 and (q+1)/4 of it.
  ElementTree one = make_element_tree(patches);
  const std::array<Vec3, 4> c = one.corner[0];
  const ElementIndex first = one.split(0, SplitKind::bands_01);
  for (int q = 0; q < 4; ++q) {
    const auto& k = one.corner[static_cast<std::size_t>(first + q)];
    CHECK((k[0] - (c[0] + 0.25 * q * (c[1] - c[0]))).norm() <= 1e-14);
    CHECK((k[3] - (c[3] + 0.25 * q * (c[2] - c[3]))).norm() <= 1e-14);
  }
  // Triangles are not cut in bands.
  CHECK_THROWS(one.split(1, SplitKind::bands_12));
}

TEST_CASE("element tree: a shared edge split in bands from either end has bit-identical points", "[hierarchy]") {
  // Two quads of a tilted plane sharing the edge P Q, listed from opposite corners so that each runs along it in
  // the other's reverse direction; coordinates whose midpoints round.
  PatchBuilder b;
  const int m = b.add_material("grey", Rgb::Constant(0.5));
  const Vec3 o(0.1, 0.3, 0.7), u = Vec3(1, 0.3, 0.1).normalized(), w0 = Vec3(-0.2, 1, 0.4);
  const Vec3 v = (w0 - w0.dot(u) * u).normalized();
  const auto at = [&](double a, double c) { return Vec3(o + a * u + c * v); };
  const Vec3 P = at(1.1, 0.1), Q = at(1.3, 1.7);
  b.add_quad(at(0, 0), P, Q, at(0.1, 1.3), m);             // edge c1 c2 = P -> Q
  b.add_quad(at(2.9, 1.9), Q, P, at(2.3, -0.2), m);        // edge c1 c2 = Q -> P
  const PatchSet patches = b.build();
  const auto on_edge = [&](const ElementTree& t, ElementIndex first) {
    std::vector<std::array<double, 3>> points;
    for (ElementIndex q = first; q < first + 4; ++q)
      for (const Vec3& x : t.corner[static_cast<std::size_t>(q)])
        if ((x - P).cross(Q - P).norm() <= 1e-9 * (Q - P).norm()) points.push_back({x.x(), x.y(), x.z()});
    std::sort(points.begin(), points.end());
    points.erase(std::unique(points.begin(), points.end()), points.end());
    return points;
  };
  ElementTree tree = make_element_tree(patches);
  const auto a = on_edge(tree, tree.split(0, SplitKind::bands_12));
  const auto c = on_edge(tree, tree.split(1, SplitKind::bands_12));
  REQUIRE(a.size() == 5);
  CHECK(a == c);  // exact equality of the doubles
  // Split twice regularly along the edge, the neighbour gets the same points as the bands.
  ElementTree twice = make_element_tree(patches);
  const ElementIndex f = twice.split(1);
  std::vector<std::array<double, 3>> r;
  for (ElementIndex q = f; q < f + 4; ++q) {
    const auto g = on_edge(twice, twice.split(static_cast<std::size_t>(q)));
    r.insert(r.end(), g.begin(), g.end());
  }
  std::sort(r.begin(), r.end());
  r.erase(std::unique(r.begin(), r.end()), r.end());
  CHECK(r == a);
}

TEST_CASE("push-pull: pushing gathered radiosity and pulling leaf radiosity conserve power exactly", "[hierarchy]") {
  const PatchSet patches = two_faces();
  ElementTree tree = make_element_tree(patches);
  const bool bands = GENERATE(false, true);
  INFO("band splits drawn: " << bands);
  grow(tree, 1000, 3, bands);
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
