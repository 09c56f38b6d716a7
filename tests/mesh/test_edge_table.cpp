// Edge topology: welding, uses and directions.
#include <catch2/catch.hpp>

#include <bit>

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

TEST_CASE("welding is exact and in order of first appearance on coordinates crafted to collide in a hash",
          "[mesh][edges]") {
  // H2: with a position hash, 40,000 vertices whose z bit patterns were solved to give one hash value took 12.6 s
  // (every insertion walked one bucket). Welding sorts instead; here the same kind of input, each position
  // twice, must weld pairwise and number the welded vertices in order of first appearance.
  Mesh mesh;
  const std::size_t n = 20000;
  for (std::size_t i = 0; i < n; ++i) {
    // x = 0, y = the double with bit pattern i + 1, z chosen so that the old hash h1 ^ (z + K + (h1 << 6) +
    // (h1 >> 2)) with h1 = y + 0x7F4A7C159E3779B9 is the same target for every vertex (z kept finite).
    const std::uint64_t y = i + 1, h1 = y + 0x7F4A7C159E3779B9ull;
    const std::uint64_t target = 0x3ff0000000000000ull;
    std::uint64_t z = ((target ^ h1) - 0x94D049BB133111EBull - (h1 << 6) - (h1 >> 2)) & ~(std::uint64_t{1} << 62);
    mesh.vertices.emplace_back(0.0, std::bit_cast<double>(y), std::bit_cast<double>(z));
  }
  for (std::size_t i = 0; i < n; ++i) mesh.vertices.push_back(mesh.vertices[n - 1 - i]);
  std::int32_t count = 0;
  const std::vector<std::int32_t> weld = weld_vertices(mesh, &count);
  CHECK(count == static_cast<std::int32_t>(n));
  int wrong = 0;
  for (std::size_t i = 0; i < n; ++i) {
    wrong += weld[i] != static_cast<std::int32_t>(i);
    wrong += weld[n + i] != static_cast<std::int32_t>(n - 1 - i);
  }
  CHECK(wrong == 0);
}
