#include "patch/patch_grouping.h"

#include <map>

#include "core/error.h"

namespace radwalk {

PatchGrouping group_patches(const PatchSet& patches, const std::string& by) {
  if (by != "object" && by != "group" && by != "material")
    throw InputError("group_by '" + by + "' is not one of object, group, material");
  PatchGrouping g;
  std::map<std::string, std::int32_t> index;
  g.group.resize(patches.size());
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const std::string& own = by == "object" ? patches.object_of(i)
                             : by == "group" ? patches.group_of(i)
                                             : patches.material_of(i);
    const std::string name = own.empty() ? "(none)" : own;
    const auto [it, fresh] = index.emplace(name, std::int32_t(g.names.size()));
    if (fresh) g.names.push_back(name);
    g.group[i] = it->second;
  }
  return g;
}

}  // namespace radwalk
