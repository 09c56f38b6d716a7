#pragma once
// Patches grouped by a name: their object, group or material (PatchSet::object_of, group_of, material_of), for
// the per-group tables and targets (heat exchange, the per-material target error).
#include <cstdint>
#include <string>
#include <vector>

#include "patch/patch_set.h"

namespace radwalk {

struct PatchGrouping {
  std::vector<std::string> names;   // in order of first patch; "(none)" for patches without a name
  std::vector<std::int32_t> group;  // per patch: its index into names
};

// by: "object", "group" or "material" (InputError naming the choices otherwise). Patches with the same name are
// one group, whatever their input faces.
PatchGrouping group_patches(const PatchSet& patches, const std::string& by);

}  // namespace radwalk
