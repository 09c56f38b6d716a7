#pragma once
// Refinement of a PatchSet: split chosen patches into 4 children each (adaptive patching).
//
//   - a quad (c0, c1, c2, c3) becomes 4 quads through its edge midpoints m01, m12, m23, m30 and its vertex centroid
//     m = (c0 + c1 + c2 + c3) / 4 (the common midpoint of m01-m23 and m12-m30):
//       (c0, m01, m, m30), (m01, c1, m12, m), (m, m12, c2, m23), (m30, m, m23, c3);
//   - a triangle (c0, c1, c2) becomes 4 triangles through its edge midpoints:
//       (c0, m01, m20), (m01, c1, m12), (m20, m12, c2), (m01, m12, m20).
// The children of a flat patch tile it exactly: they are flat, keep the parent's orientation (normal) and their
// areas add up to the parent's to rounding (a slightly non-planar quad's children follow its bilinear surface).
// Every child keeps the parent's face, material, rho and E.
//
// Conformity: an edge midpoint is created once per pair of corner points, so two split patches that share corner
// points share the midpoint of their common edge. A split patch next to an unsplit one leaves a T-junction (the
// midpoint lies inside the neighbour's edge). Radiosity is constant per patch, so T-junctions change nothing in
// the solve; they only affect smooth point fields (VTK point data averages over the patches sharing a point).
//
// Patch order: patch order is kept, a split patch is replaced in place by its 4 children (in the order above).
#include <cstdint>
#include <vector>

#include "patch/patch_set.h"
#include "patch/patching.h"

namespace radwalk {

// A guard against runaway refinement: make_patches' bound.
inline constexpr std::size_t kMaxRefinedPatchCount = kMaxPatchCount;

// split[i]: split patch i (split.size() == patches.size(), checked: InternalError). Throws InputError if the
// result would exceed kMaxRefinedPatchCount.
// If parent is given, (*parent)[k] is the index in `patches` of new patch k.
PatchSet split_patches(const PatchSet& patches, const std::vector<bool>& split,
                       std::vector<std::int32_t>* parent = nullptr);

}  // namespace radwalk
