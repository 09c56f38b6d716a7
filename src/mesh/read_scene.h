#pragma once
// Scene input: the one entry point that picks a reader by file extension.
//
//   .obj -> read_obj (OBJ + MTL, see read_obj.h)      .ply -> read_ply (PLY with face colours, see read_ply.h)
//   .stl -> read_stl (ascii and binary, read_stl.h)    .gltf, .glb -> read_gltf (glTF 2.0, read_gltf.h)
//   .vtp, .vtk -> read_vtk_polydata (VTK's readers, read_vtk.h)
// Any other extension is refused with the list of these; DAE, 3DS, FBX (and .blend, .x3d, .3mf) with a hint to
// convert them to glTF (assimp export, Blender).
//
// read_scene only reads; load_scene reads and runs validate_mesh (validate.h), which is what every computation
// should start from. Both throw InputError with a one-line message naming the file (and line and face).
#include <string>

#include "mesh/mesh.h"

namespace radwalk {

// The extensions read_scene reads, for messages: ".obj, .ply, .stl, .gltf, .glb, .vtp, .vtk".
inline constexpr const char* kSceneExtensions = ".obj, .ply, .stl, .gltf, .glb, .vtp and .vtk";

Mesh read_scene(const std::string& path, const ReadOptions& options = {});

// read_scene + validate_mesh with the default tolerances (strict as in options: repairs become refusals); a path
// that does not exist is refused first as "PATH: no such file".
Mesh load_scene(const std::string& path, const ReadOptions& options = {});

}  // namespace radwalk
