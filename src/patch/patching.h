#pragma once
// Patching: the PatchSet of a validated Mesh (run validate_mesh first), optionally subdivided.
//
// Each face is split on its own, in proportion to its own size (docs/ARCHITECTURE.md, "Patching proportionate to
// the scene"):
//   - max_edge L > 0: a face is split until none of its patch edges is longer than L; a face whose edges are all
//     at most L is not split. A quad becomes an n_u x n_v grid of quads (bilinear interpolation of its corners),
//     n_u = ceil(max(|side 0|, |side 2|) / L), n_v = ceil(max(|side 1|, |side 3|) / L); a triangle becomes m^2
//     similar triangles (uniform barycentric grid), m = ceil(longest side / L).
//   - max_area A > 0: a face is split until no patch has an area above A (combinable with max_edge: both bounds
//     hold). A triangle's m grows until area / m^2 <= A (its sub-triangles are similar to it, all of area
//     area / m^2); a quad's grid grows one row or column at a time, always across the longer side of its cells, so
//     the cells stay close to square (no slivers), until its largest cell has area <= A. (On a planar convex quad
//     the bilinear map's Jacobian is linear in (u, v), so the largest cell is a corner cell: those four are
//     checked.)
//   Cuts do not propagate: a face next to a finely split one keeps its own split (possibly none), which leaves
//   T-junctions along their common edge. Constant radiosity per patch does not care; the smooth point fields do,
//   and the display mesh (display_mesh.h) inserts the T-junction points into the neighbour's polygon.
//   Points on an edge are shared by every face that cuts the edge at the same fraction: the point at fraction p/q
//   (reduced) from the lower welded vertex is created once, so no two points coincide (a face cut in 2 and its
//   neighbour cut in 4 share the midpoint) and faces cut alike are conforming, also across non-manifold edges.
//   Sub-patches keep the parent's orientation; sub-patches of a planar face are planar and their areas add up to
//   the face's area up to rounding. A slightly non-planar quad (allowed by validate_mesh) gives sub-quads on its
//   bilinear surface, whose areas add up to its fan area only to O(twist^2).
//
// Patch order: the sub-patches of face 0 (row by row), then of face 1, ... ; with no split patch i is face i.
// Every patch keeps its input face (PatchSet::face = Mesh::source_face), material index, rho = Kd and E = pi * Ke.
// Corner points are shared: vertices with identical coordinates are welded (edge_table.h). Throws InputError for
// a NaN max_edge or max_area or when the patch count would exceed kMaxPatchCount.
#include "mesh/mesh.h"
#include "patch/patch_set.h"

namespace radwalk {

// A guard against a mistyped max_edge: twice the largest scene measured end to end (docs/scaling.md, "Ten million
// patches": about 150 bytes a patch for the PatchSet, about 700 for a ray-kernel solve with its .vtp). Every index
// holds far beyond it: patch and point indices are 32-bit (PatchIndex, corners, Embree's primitive ids: 2^31 - 1
// and 2^32 - 1), display-mesh and F offsets are 64-bit, F's 32-bit non-zero count is checked where F is built.
inline constexpr std::size_t kMaxPatchCount = 20'000'000;

struct PatchingOptions {
  double max_edge = 0;  // > 0: no patch edge longer than this (mesh units)
  double max_area = 0;  // > 0: no patch area above this (mesh units squared)
};

PatchSet make_patches(const Mesh& mesh, const PatchingOptions& options);
PatchSet make_patches(const Mesh& mesh, double max_edge);

// The distribution of the patch areas, for the run summary: count, min, median (mean of the two middle values
// for an even count) and max; all 0 for no patches.
struct PatchAreaDistribution {
  std::size_t count = 0;
  double min = 0, median = 0, max = 0;
};
PatchAreaDistribution patch_area_distribution(const PatchSet& patches);

}  // namespace radwalk
