#pragma once
// DisplayMesh: the patches as a mesh for smooth display (the point fields of the .vtp files).
//
// Smoothing groups: two patches that share a corner point, or touch along part of an edge (patch_neighbours.h),
// are in one group when they lie on one plane (normals within about 2.6 degrees, NeighbourOptions), have the same
// material and the same emitter status (E > 0 in some channel). A group is the transitive closure of that. So the
// patches of one wall form a group, while two walls meeting at a crease, a light set into a ceiling, or two
// materials side by side are separate groups.
//
// Points: every corner point is split into one display point per smoothing group that uses it, so a point field
// averaged over the patches at a display point never mixes values across a crease, a material or an emitter's
// edge. T-junctions: a corner point of a patch in the same group lying strictly inside an edge of another patch
// (left by adaptive refinement or non-conforming patching) is inserted into that patch's polygon (in edge order),
// so the display polygons are conforming: the interpolated field is continuous across the junction, with no crack
// or hole, and the value at the junction averages every patch around it, the long-edged one included.
//
// Polygon i is patch i (the same cell order): its corners in the patch's order, with any inserted T-junction
// points. Its area is the patch's (inserted points are collinear with the edge).
#include <cstdint>
#include <vector>

#include "core/types.h"
#include "patch/patch_neighbours.h"
#include "patch/patch_set.h"

namespace radwalk {

struct DisplayMesh {
  std::vector<Vec3> points;                // display points
  std::vector<std::int32_t> source_point;  // the PatchSet point each display point copies
  std::vector<std::int64_t> offsets;       // polygon i is ids[offsets[i] .. offsets[i + 1]); size patches + 1
  std::vector<std::int64_t> ids;           // display point indices of the polygons
  std::vector<std::int32_t> group;         // smoothing group of each patch, 0 .. groups - 1
  std::size_t groups = 0;
};

DisplayMesh make_display_mesh(const PatchSet& patches, const NeighbourOptions& options = {});

// The point field of a per-patch field (values: patches x components, patch-major): at each display point the
// area-weighted mean over the polygons that use it (all of one smoothing group). Non-finite patch values are left
// out of the mean; a point whose patches are all non-finite gets NaN. Result: points x components.
std::vector<double> point_average(const DisplayMesh& mesh, const PatchSet& patches, const std::vector<double>& values,
                                  int components);

}  // namespace radwalk
