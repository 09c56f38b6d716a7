#pragma once
// Contact pairs: two patches lying on each other back to back, e.g. the piece of a floor cut along a cabinet's
// footprint (patch/contact.h, --contact-cut) and the cabinet's bottom patch with the same corners. Each sees only
// the other's back, so both are contact patches (contact_patches.h). A scene file cannot tell such a pair from a
// thin part modelled as two faces, which the readers' validation merges into one two-sided face
// (mesh/validate.h); radwalk's .vtp therefore names its pairs (the cell field `contact_pair`, io/cell_field.h), and
// its reader keeps them as two one-sided faces (mesh/read_vtk.h), so that a .vtp reads back cell for cell.
//
// Patches i and j (i < j) are a pair iff both are front patches (Side::one_sided or Side::front: a back patch is
// its own front's reversed copy, never a contact), their corner positions are the same set of points
// (bit-identical coordinates, which is what the readers weld: mesh/exact_vertices.h, mesh/edge_table.h), their
// normals point opposite ways (n_i . n_j < 0), and no other front patch has those corners.
#include <cstdint>
#include <vector>

#include "patch/patch_set.h"

namespace radwalk {

// The pair id of every patch: 0, 1, ... numbering the pairs in the order of their lower patch index; -1 for a
// patch in no pair. O(N log N).
std::vector<std::int32_t> contact_pair_ids(const PatchSet& patches);

}  // namespace radwalk
