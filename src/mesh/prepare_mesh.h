#pragma once
// The steps between reading a scene and patching it, in the one order every reader of a scene takes them (the
// CLI's --scale, --set, --rho-scale, --strict, --orient and --open-shells, and radwalk.load's arguments of the
// same names): coordinates scaled (length_unit.h), material overrides applied (material_override.h), then
// validation with its repairs and orientation (validate.h).
#include <string>
#include <vector>

#include "mesh/length_unit.h"
#include "mesh/material_override.h"
#include "mesh/mesh.h"
#include "mesh/validate.h"

namespace radwalk {

struct MeshPreparation {
  double scale = 1;                         // every coordinate times this (finite, > 0)
  std::vector<MaterialOverride> overrides;  // --set, in order
  double rho_scale = 1;                     // every Kd times this, after the overrides
  ValidationTolerances tolerances;          // strict, orient, open shells
};

// The length unit of a file in `unit` (mm, cm, m, in, ft, or "" for the file's own) scaled by `scale`. Throws
// InputError naming the valid units for another name, and for a scale that is not finite and > 0.
LengthUnit checked_length_unit(const std::string& unit, double scale);

// scale_mesh(mesh, p.scale), apply_material_overrides(mesh, p.overrides, p.rho_scale), validate_mesh(mesh,
// p.tolerances), in this order; their exceptions pass through (MeshRefused with every finding).
void prepare_mesh(Mesh& mesh, const MeshPreparation& p);

}  // namespace radwalk
