#include "mesh/mesh.h"

#include "core/error.h"
#include "core/excerpt.h"

namespace radwalk {

std::string Mesh::context(std::size_t f) const {
  return context_of(f < face_material.size() ? face_material[f] : -1, f < face_group.size() ? face_group[f] : -1);
}

std::string Mesh::context_of(std::int32_t material, std::int32_t group) const {
  std::string parts;
  if (group >= 0 && static_cast<std::size_t>(group) < groups.size())
    parts = excerpt(groups[static_cast<std::size_t>(group)]);
  if (material >= 0 && static_cast<std::size_t>(material) < materials.size())
    parts += (parts.empty() ? "" : ", ") + ("material '" +
                                                  excerpt(materials[static_cast<std::size_t>(material)].name) + "'");
  return parts.empty() ? std::string() : " (" + printable(parts) + ")";
}

Finding Mesh::finding(std::size_t f, std::string kind, Severity severity, std::string message) const {
  return finding_of(source_face(f), f < face_line.size() ? face_line[f] : 0,
                    f < face_material.size() ? face_material[f] : -1, f < face_group.size() ? face_group[f] : -1,
                    std::move(kind), severity, std::move(message));
}

Finding Mesh::finding_of(long source, long line, std::int32_t material, std::int32_t group, std::string kind,
                         Severity severity, std::string message) const {
  Finding out;
  out.kind = std::move(kind);
  out.severity = severity;
  out.file = path;
  out.line = line;
  out.face = source;
  out.message = std::move(message);
  const auto g = static_cast<std::size_t>(group);
  if (group >= 0 && g < groups.size()) {
    if (g < group_object.size() && g < group_name.size()) {
      out.object = group_object[g];
      out.group = group_name[g];
    } else {
      out.group = groups[g];  // a label without its parts
    }
  }
  if (material >= 0 && static_cast<std::size_t>(material) < materials.size())
    out.material = materials[static_cast<std::size_t>(material)].name;
  return out;
}

}  // namespace radwalk
