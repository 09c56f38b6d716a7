#pragma once
// The scene as the user gave it: vertices, faces (triangles or quads) and materials, before patching.
// Face f is input face f everywhere in radwalk (messages, CSV `face` column, patch-to-face map).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/types.h"
#include "mesh/material.h"

namespace radwalk {

struct Mesh {
  std::string path;                              // file it came from (for messages)
  std::vector<Vec3> vertices;
  std::vector<std::array<std::int32_t, 4>> faces;  // vertex indices; [3] == -1 for a triangle
  std::vector<std::int32_t> face_material;       // index into materials
  std::vector<long> face_line;                   // source line of the face (OBJ), 0 if unknown
  std::vector<Material> materials;
  std::vector<std::string> warnings;             // one line per repair or notice, naming the face

  std::size_t face_count() const { return faces.size(); }
  bool is_quad(std::size_t f) const { return faces[f][3] >= 0; }
  int corner_count(std::size_t f) const { return is_quad(f) ? 4 : 3; }
};

}  // namespace radwalk
