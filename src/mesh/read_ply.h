#pragma once
// Stanford PLY input through OpenMesh (ascii or binary).
//
// Reads vertex positions and, if the face element has red/green/blue properties, a per-face colour used as the
// diffuse reflectance rho = colour / 255 (one material per distinct colour, named "ply_R_G_B"). Without face colours
// every face gets rho 0.5 with a warning. PLY carries no emission (OpenMesh reads no such property): a PLY scene has
// no emitter unless one is added later.
//
// OpenMesh silently drops some faces (repeated vertex indices) and re-adds non-manifold ones on duplicated
// vertices. The header's face count is read here and compared with what OpenMesh returns: a difference is an
// InputError, so that face f stays the f-th face of the file. Whatever OpenMesh writes to omerr while reading is
// turned into warnings. For ascii files face_line holds the line of each face (one element per line assumed);
// for binary files it is 0.
// Not thread-safe: OpenMesh's error stream is global.
#include <string>

#include "mesh/mesh.h"

namespace radwalk {

Mesh read_ply(const std::string& path);

}  // namespace radwalk
