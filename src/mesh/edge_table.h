#pragma once
// The edge topology of a Mesh, for validation and patching.
//
// Vertices with bit-identical coordinates are welded into one (exported OBJ/PLY files often repeat a vertex per
// face, and OpenMesh duplicates vertices of non-manifold faces). An edge is an unordered pair of welded vertices;
// each face side k (corner k -> corner k+1, cyclic) is one use of its edge. Unlike a halfedge structure this
// represents any input: edges used by 1 face (boundary), 2 faces (manifold) or 3+ faces (non-manifold, legal for
// radiosity) alike.
#include <array>
#include <cstdint>
#include <vector>

#include "mesh/mesh.h"

namespace radwalk {

struct EdgeUse {
  std::int32_t face = -1;
  std::int8_t side = 0;   // corner side -> side + 1 of the face
  bool forward = false;   // the face runs the edge from its lower welded vertex to its higher one
};

struct EdgeTable {
  std::vector<std::int32_t> weld;                         // mesh vertex -> welded vertex
  std::vector<std::int32_t> welded_source;                // welded vertex -> first mesh vertex at that position
  std::vector<std::array<std::int32_t, 2>> edges;         // welded endpoints, [0] <= [1]
  std::vector<std::array<std::int32_t, 4>> face_edge;     // edge of each face side, -1 for a triangle's side 3
  std::vector<std::int32_t> use_offset;                   // uses of edge e: uses[use_offset[e], use_offset[e + 1])
  std::vector<EdgeUse> uses;                              // grouped by edge, in face order within an edge

  std::size_t edge_count() const { return edges.size(); }
  std::int32_t use_count(std::size_t e) const { return use_offset[e + 1] - use_offset[e]; }
  const EdgeUse* uses_begin(std::size_t e) const { return uses.data() + use_offset[e]; }
  const EdgeUse* uses_end(std::size_t e) const { return uses.data() + use_offset[e + 1]; }
};

// Welded vertex id per mesh vertex (ids in order of first appearance) and the number of welded vertices.
std::vector<std::int32_t> weld_vertices(const Mesh& mesh, std::int32_t* welded_count = nullptr);

// Builds the table. Precondition: every face index is in range (validate_mesh checks this first).
EdgeTable build_edge_table(const Mesh& mesh);

}  // namespace radwalk
