#pragma once
// The leaves of an element tree as a PatchSet, so every per-patch output (the .vtp, the CSV with its input face,
// object, group and material columns) and every per-patch estimator (the discretisation error) works on them.
//
// Leaf k of `leaves` becomes patch k: its corners (welded by exact coordinates: shared corners of neighbouring
// elements are bit-identical, element_tree.h), and from its root patch r the input face, material, reflectance,
// emission and side; geometry recomputed from the corners (compute_patch_geometry). The names (input_face_group,
// group_object, group_name, materials, source) are copied, so the outputs name every leaf's input face.
#include <vector>

#include "hierarchy/element_tree.h"
#include "patch/patch_set.h"

namespace radwalk {

PatchSet leaf_patches(const PatchSet& roots, const ElementTree& tree, const std::vector<ElementIndex>& leaves);

}  // namespace radwalk
