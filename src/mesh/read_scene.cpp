#include "mesh/read_scene.h"

#include <filesystem>

#include "core/error.h"
#include "mesh/read_obj.h"
#include "mesh/read_ply.h"
#include "mesh/text_scan.h"
#include "mesh/validate.h"

namespace radwalk {

Mesh read_scene(const std::string& path, const ReadOptions& options) {
  const std::string ext = lower_extension(path);
  if (ext == "obj") return read_obj(path, options);
  if (ext == "ply") return read_ply(path, options);
  throw InputError(locate(path, 0, -1, "unknown scene format '." + ext + "' (radwalk reads .obj and .ply)"));
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
