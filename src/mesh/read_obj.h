#pragma once
// Wavefront OBJ + MTL input.
//
// Face f of the Mesh is the f-th `f` statement of the file (0-based, across groups and objects); face_line[f] is
// its line. Vertices keep file order (vertex i = i-th `v` statement). Materials come from the `mtllib` files in
// statement order, newmtl blocks in file order (see mtl.h for the statements and the BsdfKind mapping); a face
// before any `usemtl` gets material -1 (validate_mesh gives it a default with a warning).
//
// tinyobjloader parses the structure (faces, material assignment, MTL blocks). A light line scan of both files
// supplies what tinyobjloader does not give or papers over, and the two are cross-checked face by face:
//   - source lines of faces and materials;
//   - exact numbers (tinyobjloader's parser is off by one ulp for 0.73; it reads "nan" as 0 and a short
//     `v 1 2` or `Kd 0.5` line as zeros);
//   - strictness: a vertex without three finite coordinates, a face with fewer than 3 or more than 4 vertices, index
//     0 or a relative index before the first vertex, a missing mtllib file, an unknown usemtl name (when a face
//     uses it) are InputErrors naming file, line and face. `l` and `p` statements are ignored with a warning.
// Out-of-range vertex indices are kept and reported by validate_mesh.
#include <string>

#include "mesh/mesh.h"

namespace radwalk {

Mesh read_obj(const std::string& path);

}  // namespace radwalk
