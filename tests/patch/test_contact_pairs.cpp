// Contact pairs (patch/contact_pairs.h): two front patches on the same corners facing opposite ways, and nothing
// else: not two patches facing the same way, not a two-sided face's front and back, not three on one place.
#include <catch2/catch.hpp>

#include <vector>

#include "patch/contact_pairs.h"
#include "patch/patch_builder.h"

using namespace radwalk;

TEST_CASE("contact pairs: a floor piece and the bottom lying on it are a pair, other coincident patches are not",
          "[patch][contact]") {
  PatchBuilder b;
  const int floor = b.add_material("floor", Rgb::Constant(0.5));
  const int box = b.add_material("box", Rgb::Constant(0.4));
  // 0: a floor piece facing up; 1: another beside it; 2: a box's bottom on piece 0, facing down, its corners
  // starting elsewhere (the same points in another order); 3: a box side rising from piece 0's edge.
  b.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, floor);
  b.add_quad({1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, floor);
  b.add_quad({1, 1, 0}, {1, 0, 0}, {0, 0, 0}, {0, 1, 0}, box);
  b.add_quad({0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}, box);
  // 4, 5: two triangles on one place facing the same way (an overlap, not a contact).
  b.add_triangle({0, 0, 3}, {1, 0, 3}, {0, 1, 3}, floor);
  b.add_triangle({1, 0, 3}, {0, 1, 3}, {0, 0, 3}, floor);
  // 6, 7, 8: three quads on one place, two facing up, one down: no pair (which two would it be?).
  b.add_quad({5, 0, 0}, {6, 0, 0}, {6, 1, 0}, {5, 1, 0}, floor);
  b.add_quad({5, 0, 0}, {6, 0, 0}, {6, 1, 0}, {5, 1, 0}, floor);
  b.add_quad({5, 0, 0}, {5, 1, 0}, {6, 1, 0}, {6, 0, 0}, box);
  // 9, 10: a triangle lying on a triangle, back to back: the second pair.
  b.add_triangle({0, 0, 5}, {1, 0, 5}, {0, 1, 5}, floor);
  b.add_triangle({0, 0, 5}, {0, 1, 5}, {1, 0, 5}, box);
  // 11: a triangle on three of piece 1's corners is not piece 1 (a different set of points).
  b.add_triangle({1, 1, 0}, {2, 1, 0}, {1, 0, 0}, box);
  PatchSet p = b.build();
  REQUIRE(contact_pair_ids(p) == std::vector<std::int32_t>{0, -1, 0, -1, -1, -1, -1, -1, -1, 1, 1, -1});

  // A two-sided floor piece: its back patch (the reversed copy, appended) is no contact of its front, and the
  // bottom lying on the front still pairs with the front only.
  p.materials[static_cast<std::size_t>(floor)].two_sided = true;
  REQUIRE(add_back_sides(p) > 0);
  const std::vector<std::int32_t> ids = contact_pair_ids(p);
  REQUIRE(ids.size() == p.size());
  for (std::size_t i = 12; i < p.size(); ++i) REQUIRE(ids[i] == -1);  // the back patches
  REQUIRE(std::vector<std::int32_t>(ids.begin(), ids.begin() + 12) ==
          std::vector<std::int32_t>{0, -1, 0, -1, -1, -1, -1, -1, -1, 1, 1, -1});
}
