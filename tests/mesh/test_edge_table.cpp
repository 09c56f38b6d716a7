// Edge topology: welding, uses and directions.
#include <catch2/catch.hpp>

#include "mesh/edge_table.h"

using namespace radwalk;

TEST_CASE("edge table welds coincident vertices and records each side's direction", "[mesh][edges]") {
  // Two unit squares side by side, each with its own copy of the shared vertices (as exporters write them).
  Mesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},  // square A
                   {1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}};  // square B (copies of A's right side)
  mesh.faces = {{0, 1, 2, 3}, {4, 5, 6, 7}};
  const EdgeTable t = build_edge_table(mesh);
  CHECK(t.welded_source.size() == 6);
  CHECK(t.weld[4] == t.weld[1]);
  CHECK(t.weld[7] == t.weld[2]);
  CHECK(t.edge_count() == 7);
  // A's side 1 (1 -> 2) and B's side 3 (7 -> 4, i.e. 2 -> 1) are one edge used twice in opposite directions.
  const auto e = static_cast<std::size_t>(t.face_edge[0][1]);
  CHECK(t.face_edge[1][3] == static_cast<std::int32_t>(e));
  REQUIRE(t.use_count(e) == 2);
  CHECK(t.uses_begin(e)[0].face == 0);
  CHECK(t.uses_begin(e)[1].face == 1);
  CHECK(t.uses_begin(e)[0].forward != t.uses_begin(e)[1].forward);
  int boundary = 0;
  for (std::size_t k = 0; k < t.edge_count(); ++k) boundary += t.use_count(k) == 1;
  CHECK(boundary == 6);
  // -0.0 and +0.0 weld.
  Mesh signed_zero;
  signed_zero.vertices = {{0, 0, 0}, {-0.0, 0, 0}};
  CHECK(weld_vertices(signed_zero)[1] == 0);
}
