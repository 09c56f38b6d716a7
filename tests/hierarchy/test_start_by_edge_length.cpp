// The start of --hierarchical --target-error given no patching (hierarchy/start_by_edge_length.h): deterministic
// counts on the unit cube room, whose six unit faces halve their edges at each round of quarters.
#include <catch2/catch.hpp>

#include "hierarchy/start_by_edge_length.h"
#include "support/box_scenes.h"

namespace radwalk {

// 6 unit faces and 100 more: the rounds give 24 leaves (edges 1/2, for L < 1), 96 (edges 1/4, L < 1/2) and 384
// (edges 1/8, L < 1/4); 96 < 106, so the largest L is just below 1/4 and the start is the 384, 64 under each root.
TEST_CASE("start by edge length: the roots and `more` leaves at the largest edge length that gives them",
          "[hierarchy][target_error]") {
  const PatchSet roots = test::unit_cube_room(1);
  REQUIRE(roots.size() == 6);
  const HierarchicalOptions solve;
  const ElementTree tree = start_by_edge_length(roots, 100, 20000, true, solve);
  const std::vector<ElementIndex> leaves = tree.leaves();
  CHECK(leaves.size() == 384);
  double area = 0;
  for (const ElementIndex e : leaves) {
    CHECK(tree.level[std::size_t(e)] == 3);  // every leaf 1/8 on a side: three rounds of quarters
    area += tree.area[std::size_t(e)];
  }
  CHECK(area == Approx(roots.total_area()).epsilon(1e-12));
  // Within the budget: a round to 384 would pass 200, so the rounds stop at 96.
  CHECK(start_by_edge_length(roots, 100, 200, true, solve).leaves().size() == 96);
  // Within the depth: max_level 1 stops at the first round.
  HierarchicalOptions shallow;
  shallow.max_level = 1;
  CHECK(start_by_edge_length(roots, 100, 20000, true, shallow).leaves().size() == 24);
  // 18 more: 24 are enough, each root quartered once; 0 more: the roots themselves.
  CHECK(start_by_edge_length(roots, 18, 20000, true, solve).leaves().size() == 24);
  CHECK(start_by_edge_length(roots, 0, 20000, true, solve).leaves().size() == 6);
}

}  // namespace radwalk
