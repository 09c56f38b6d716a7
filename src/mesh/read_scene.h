#pragma once
// Scene input: the one entry point that picks a reader by file extension.
//
//   .obj -> read_obj (OBJ + MTL, see read_obj.h)      .ply -> read_ply (PLY with face colours, see read_ply.h)
//
// read_scene only reads; load_scene reads and runs validate_mesh (validate.h), which is what every computation
// should start from. Both throw InputError with a one-line message naming the file (and line and face).
#include <string>

#include "mesh/mesh.h"

namespace radwalk {

Mesh read_scene(const std::string& path, const ReadOptions& options = {});

// read_scene + validate_mesh with the default tolerances (strict as in options: repairs become refusals); a path
// that does not exist is refused first as "PATH: no such file".
Mesh load_scene(const std::string& path, const ReadOptions& options = {});

}  // namespace radwalk
