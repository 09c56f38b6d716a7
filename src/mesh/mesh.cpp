#include "mesh/mesh.h"

#include "core/error.h"

namespace radwalk {

std::string Mesh::context(std::size_t f) const {
  std::string parts;
  if (f < face_group.size() && face_group[f] >= 0 && static_cast<std::size_t>(face_group[f]) < groups.size())
    parts = groups[static_cast<std::size_t>(face_group[f])];
  if (f < face_material.size() && face_material[f] >= 0 &&
      static_cast<std::size_t>(face_material[f]) < materials.size())
    parts += (parts.empty() ? "" : ", ") + ("material '" + materials[static_cast<std::size_t>(face_material[f])].name + "'");
  return parts.empty() ? std::string() : " (" + printable(parts) + ")";
}

}  // namespace radwalk
