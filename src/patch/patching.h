#pragma once
// Patching: the PatchSet of a validated Mesh (run validate_mesh first), optionally subdivided.
//
// max_edge <= 0: patch i is input face i (quads stay one patch).
// max_edge > 0: faces are split until no patch edge is longer than max_edge:
//   - edges are grouped into classes that must be split alike (union-find: a quad's opposite sides, all three
//     sides of a triangle), and every edge of a class is cut into n = ceil(longest edge of the class / max_edge)
//     equal parts, so a quad's opposite sides match and a triangle's sides match;
//   - a quad becomes an n_u x n_v grid of quads (bilinear interpolation of its corners), a triangle n^2 triangles
//     (uniform barycentric grid); the sub-patches keep the parent's orientation;
//   - the split points of an edge are created once, from its canonical direction (lower welded vertex first), and
//     shared by every face on that edge: no T-junctions, also across non-manifold edges.
//   Sub-patches of a planar face are planar and their areas add up to the face's area up to rounding; no patch edge
//   is longer than max_edge (up to rounding). A slightly non-planar quad (allowed by validate_mesh) gives
//   sub-quads on its bilinear surface, whose areas add up to its fan area only to O(twist^2).
//
// Patch order: the sub-patches of face 0 (row by row), then of face 1, ... . Every patch keeps its input face
// (PatchSet::face), material index, rho = Kd and E = pi * Ke. Corner points are shared: vertices with identical
// coordinates are welded (edge_table.h). Throws InputError for a NaN max_edge or when the patch count would
// exceed kMaxPatchCount.
#include "mesh/mesh.h"
#include "patch/patch_set.h"

namespace radwalk {

// A guard against a mistyped max_edge: far more patches than any solver here can use (about 150 bytes each).
inline constexpr std::size_t kMaxPatchCount = 10'000'000;

PatchSet make_patches(const Mesh& mesh, double max_edge);

}  // namespace radwalk
