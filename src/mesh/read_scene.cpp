#include "mesh/read_scene.h"

#include <filesystem>

#include "core/error.h"
#include "core/excerpt.h"
#include "mesh/read_obj.h"
#include "mesh/read_gltf.h"
#include "mesh/read_ply.h"
#include "mesh/read_stl.h"
#include "mesh/read_vtk.h"
#include "mesh/text_scan.h"
#include "mesh/validate.h"

namespace radwalk {

Mesh read_scene(const std::string& path, const ReadOptions& options) {
  const std::string ext = lower_extension(path);
  if (ext == "obj") return read_obj(path, options);
  if (ext == "ply") return read_ply(path, options);
  if (ext == "stl") return read_stl(path, options);
  if (ext == "gltf" || ext == "glb") return read_gltf(path, options);
  if (ext == "vtp" || ext == "vtk") return read_vtk_polydata(path, options);
  const std::string known = "radwalk reads " + std::string(kSceneExtensions);
  if (ext == "dae" || ext == "3ds" || ext == "fbx" || ext == "blend" || ext == "x3d" || ext == "3mf")
    throw InputError(locate(path, 0, -1, "." + ext + " is not read (" + known + "): convert it to glTF, e.g. "
                                             "'assimp export " + path + " " +
                                             std::filesystem::path(path).replace_extension(".glb").string() +
                                             "' (package assimp-utils) or "
                                             "Blender's File > Export > glTF 2.0"));
  throw InputError(locate(path, 0, -1, (ext.empty() ? std::string("no file extension to tell the format")
                                                    : "unknown scene format '." + excerpt(ext) + "'") +
                                           " (" + known + ")"));
}

Mesh load_scene(const std::string& path, const ReadOptions& options) {
  if (!std::filesystem::exists(path)) throw InputError(path + ": no such file");
  Mesh mesh = read_scene(path, options);
  ValidationTolerances tolerances;
  tolerances.strict = options.strict;
  validate_mesh(mesh, tolerances);
  return mesh;
}

}  // namespace radwalk
