#include "mesh/mesh_from_arrays.h"

#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include "core/error.h"
#include "mesh/polygon_faces.h"

namespace radwalk {
namespace {

// The group of every distinct name in order of first use, as the OBJ reader numbers `g NAME` groups.
std::vector<std::int32_t> group_indices(const std::vector<std::string>& names, Mesh& mesh) {
  std::vector<std::int32_t> index(names.size(), -1);
  std::map<std::string, std::int32_t> known;
  for (std::size_t f = 0; f < names.size(); ++f) {
    if (names[f].empty()) continue;
    auto [it, added] = known.emplace(names[f], static_cast<std::int32_t>(mesh.groups.size()));
    if (added) {
      mesh.groups.push_back("group '" + names[f] + "'");
      mesh.group_object.push_back("");
      mesh.group_name.push_back(names[f]);
    }
    index[f] = it->second;
  }
  return index;
}

}  // namespace

Mesh mesh_from_arrays(const FaceArrays& arrays, const std::string& name, const ReadOptions& options) {
  Mesh mesh;
  mesh.path = name;
  mesh.vertices = arrays.vertices;
  const std::size_t n_faces = arrays.faces.size();
  if (n_faces > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    throw InputError(name + ": too many faces");
  if (mesh.vertices.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    throw InputError(name + ": too many vertices");
  const auto per_face = [&](const char* what, std::size_t n, bool optional) {
    if ((optional && n == 0) || n == n_faces) return;
    throw InputError(name + ": " + what + " has " + std::to_string(n) + " rows for " + std::to_string(n_faces) +
                     " faces");
  };
  per_face("rho", arrays.rho.size(), false);
  per_face("emission", arrays.emission.size(), true);
  per_face("groups", arrays.group.size(), true);

  const std::vector<std::int32_t> group =
      arrays.group.empty() ? std::vector<std::int32_t>(n_faces, -1) : group_indices(arrays.group, mesh);

  // Materials: the distinct (rho, E) pairs in order of their first face.
  std::map<std::tuple<double, double, double, double, double, double>, std::int32_t> material_of;
  PolygonFaces faces(mesh, options.strict);
  for (std::size_t f = 0; f < n_faces; ++f) {
    const Rgb rho = arrays.rho[f];
    const Rgb E = arrays.emission.empty() ? Rgb::Zero() : arrays.emission[f];
    const auto key = std::make_tuple(rho[0], rho[1], rho[2], E[0], E[1], E[2]);
    auto [it, added] = material_of.emplace(key, static_cast<std::int32_t>(mesh.materials.size()));
    if (added) {
      Material m;
      m.name = "material_" + std::to_string(mesh.materials.size());
      m.Kd = rho;
      m.Ke = E / kPi;
      mesh.materials.push_back(m);
    }
    const std::int32_t material = it->second;
    const auto source = static_cast<std::int32_t>(f);
    const std::vector<std::int64_t>& input = arrays.faces[f];
    if (input.size() < 3) {
      mesh.findings.push_back(mesh.finding_of(source, 0, material, group[f], "too few corners", Severity::error,
                                              "has " + std::to_string(input.size()) +
                                                  " corners; a face needs at least 3"));
      continue;
    }
    std::vector<std::int32_t> corners;
    std::string bad;
    for (std::int64_t v : input) {
      if (v < 0 || static_cast<std::uint64_t>(v) >= mesh.vertices.size()) {
        bad = "bad vertex index: vertex " + std::to_string(v) + " (counting from 0) does not exist, there are " +
              std::to_string(mesh.vertices.size()) + " vertices";
        break;
      }
      corners.push_back(static_cast<std::int32_t>(v));
    }
    if (!bad.empty()) {
      mesh.findings.push_back(mesh.finding_of(source, 0, material, group[f], "bad vertex index", Severity::error, bad));
      continue;
    }
    faces.add(corners, 0, material, group[f], source);
  }
  return mesh;
}

}  // namespace radwalk
