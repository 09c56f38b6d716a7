#include "mesh/read_scene.h"

#include "core/error.h"
#include "mesh/read_obj.h"
#include "mesh/read_ply.h"
#include "mesh/text_scan.h"
#include "mesh/validate.h"

namespace radwalk {

Mesh read_scene(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == "obj") return read_obj(path);
  if (ext == "ply") return read_ply(path);
  throw InputError(locate(path, 0, -1, "unknown scene format '." + ext + "' (radwalk reads .obj and .ply)"));
}

Mesh load_scene(const std::string& path) {
  Mesh mesh = read_scene(path);
  validate_mesh(mesh);
  return mesh;
}

}  // namespace radwalk
