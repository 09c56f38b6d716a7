#pragma once
// T-junctions and closed shells of a Mesh, from its boundary edges (edges used by one face, edge_table.h).
//
// A T-junction is a vertex that lies strictly inside a boundary edge a - b of another face without being a
// corner of that face: the faces on one side of the edge are cut at the T point, the face on the other side is
// not, so the edge a - b and the edges a - v, v - b are each used once although the surface is closed there.
// A point p lies on a - b when its distance to the segment is at most rel_tolerance x |b - a| and its parameter
// t = (p - a).(b - a) / |b - a|^2 is in (rel_tolerance, 1 - rel_tolerance).
//
// A boundary edge is covered when it holds a T point or lies on another boundary edge (its midpoint is on that
// edge): the surface goes on across it. The mesh is a closed shell when every boundary edge is covered (and so
// every edge is used at least twice, or is covered by a T-junction).
//
// Cost: a uniform grid over the boundary vertices and edge midpoints (cell = the median boundary-edge length);
// each boundary edge visits the cells its bounding box covers.
#include <cstdint>
#include <vector>

#include "mesh/edge_table.h"
#include "mesh/mesh.h"

namespace radwalk {

struct TJunction {
  std::int32_t edge = -1;    // the boundary edge the point lies on (EdgeTable::edges index)
  std::int32_t face = -1;    // the face using that edge
  std::int32_t vertex = -1;  // the T point: a welded vertex (EdgeTable::welded_source names it)
  double t = 0;              // its parameter along edges[edge][0] -> edges[edge][1]
};

struct BoundaryCover {
  std::vector<TJunction> t_junctions;  // sorted by edge, then t
  std::vector<bool> covered;           // per edge: used 2+ times, or covered as above
  std::size_t boundary_edges = 0;      // edges used by one face
  std::size_t uncovered = 0;           // boundary edges not covered
  bool closed() const { return uncovered == 0; }
};

// Precondition: every face index is in range and every coordinate finite (validate_mesh checks this first).
BoundaryCover find_t_junctions(const Mesh& mesh, const EdgeTable& table, double rel_tolerance = 1e-9);

// The faces form a closed surface (rays leaving any face land on one), T-junctions allowed: either all of them
// (find_t_junctions(mesh, build_edge_table(mesh)).closed()), or the room around everything does:
// encloses(mesh, enclosure_faces(mesh)). So a closed room with open objects in it (a table top as one sheet)
// counts as closed, and rays that escape it are reported.
bool is_closed_shell(const Mesh& mesh);

// The faces of the room around the scene: all corners on one plane of the bounding box (to 1e-9 of its
// diagonal) and facing into the box. An object's bottom on the floor or back against a wall faces out: not one.
std::vector<std::size_t> enclosure_faces(const Mesh& mesh);

// These faces alone form a closed shell (find_t_junctions on the sub-mesh; false for none).
bool encloses(const Mesh& mesh, const std::vector<std::size_t>& faces);

}  // namespace radwalk
