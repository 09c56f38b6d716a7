#pragma once
// Edge neighbours of patches: which patches touch along (part of) an edge on the same surface.
//
// Patches i != j are edge neighbours when
//   - an edge of i and an edge of j are collinear (both end points of one within `tol` of the other's line) and
//     overlap along a segment longer than `tol` (a whole shared edge, or part of one at a T-junction), and
//   - their normals agree: n_i . n_j >= min_normal_dot (they lie on the same plane, facing the same way).
// So patches meeting at a crease (wall and floor), back to back, or touching at a single corner are not
// neighbours. Found geometrically (corner points need not be shared, PatchBuilder's sets work too):
// tol = relative_tolerance x scene_extent(). Cost: O(edges) with a uniform grid of cells about the median edge
// length.
#include <utility>
#include <vector>

#include "core/types.h"
#include "patch/patch_set.h"

namespace radwalk {

struct NeighbourOptions {
  double min_normal_dot = 0.999;       // cos of about 2.6 degrees
  double relative_tolerance = 1e-7;    // of the scene extent
};

// Every neighbouring pair once, as (i, j) with i < j, sorted.
std::vector<std::pair<PatchIndex, PatchIndex>> edge_neighbours(const PatchSet& patches,
                                                               const NeighbourOptions& options = {});

}  // namespace radwalk
