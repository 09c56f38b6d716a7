#include "mesh/prepare_mesh.h"

#include <cmath>

#include "core/error.h"

namespace radwalk {

LengthUnit checked_length_unit(const std::string& unit, double scale) {
  if (!unit.empty() && metres_per(unit) == 0)
    throw InputError("unit '" + printable(unit) + "' is not one of " + unit_names());
  if (!(std::isfinite(scale) && scale > 0))
    throw InputError("scale " + std::to_string(scale) + " must be a finite number > 0");
  LengthUnit u;
  u.file_unit = unit;
  u.scale = scale;
  return u;
}

void prepare_mesh(Mesh& mesh, const MeshPreparation& p) {
  scale_mesh(mesh, p.scale);
  apply_material_overrides(mesh, p.overrides, p.rho_scale);
  validate_mesh(mesh, p.tolerances);
}

}  // namespace radwalk
