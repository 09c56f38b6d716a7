#include "mesh/mesh.h"

#include "core/error.h"

namespace radwalk {

std::string Mesh::context(std::size_t f) const {
  return context_of(f < face_material.size() ? face_material[f] : -1, f < face_group.size() ? face_group[f] : -1);
}

std::string Mesh::context_of(std::int32_t material, std::int32_t group) const {
  std::string parts;
  if (group >= 0 && static_cast<std::size_t>(group) < groups.size()) parts = groups[static_cast<std::size_t>(group)];
  if (material >= 0 && static_cast<std::size_t>(material) < materials.size())
    parts += (parts.empty() ? "" : ", ") + ("material '" + materials[static_cast<std::size_t>(material)].name + "'");
  return parts.empty() ? std::string() : " (" + printable(parts) + ")";
}

}  // namespace radwalk
