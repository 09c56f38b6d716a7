#pragma once
// A scene given as arrays instead of a file (the Python module's Scene.from_arrays): the same Mesh, and so the
// same validation, repairs and patches, as the OBJ + MTL that says the same thing.
//
// Contract: vertices in the mesh's length unit; faces as lists of 0-based vertex indices (3 or more corners; a
// polygon goes through the readers' one rule, polygon_faces.h: triangulated, split where it crosses itself,
// dropped when it has no area, each a repair with its finding); per face the reflectance rho and the emitted
// radiosity (exitance) E in W/m^2 per channel, so that the material's Ke is E / pi as in an MTL; optionally a group
// name per face ("" for none), as OBJ `g NAME` gives. The materials are the distinct (rho, E) pairs in the order
// of their first face, named "material_0", "material_1", ...: the OBJ whose MTL defines them under these names
// (Kd = rho, Ke = E / pi) and whose faces use them is read into the same Mesh, up to `path` and the faces' lines
// (0 here). Arrays of the wrong length, a face of fewer than 3 corners or a corner out of range are findings
// (errors), collected with the others; validate_mesh then refuses the scene with all of them, as for a file.
#include <cstdint>
#include <string>
#include <vector>

#include "core/types.h"
#include "mesh/mesh.h"

namespace radwalk {

struct FaceArrays {
  std::vector<Vec3> vertices;
  std::vector<std::vector<std::int64_t>> faces;
  std::vector<Rgb> rho;       // one per face
  std::vector<Rgb> emission;  // E, W/m^2, one per face (empty: no emission)
  std::vector<std::string> group;  // one per face, or empty
};

// The Mesh of the arrays, not yet validated (load_scene's read step); `name` stands for the file in messages.
Mesh mesh_from_arrays(const FaceArrays& arrays, const std::string& name, const ReadOptions& options = {});

}  // namespace radwalk
