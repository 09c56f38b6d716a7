#pragma once
// Material overrides from the command line (--set MATERIAL.Kd=r,g,b, --set MATERIAL.Ke=r,g,b, --rho-scale s):
// a sweep over rho or emission needs no copies of the MTL file.
//
// An override replaces the property of the named material as if its MTL block said so: `--set wall.Kd=0.2,0.3,0.4`
// is `Kd 0.2 0.3 0.4` in `newmtl wall`, and a single value is grey (`--set light.Ke=10` is `Ke 10`). Numbers
// follow the MTL rule (text_scan.h parse_number: exact, finite). The material name is the text before the last
// '.' before '='. The rho scale multiplies every material's Kd, after the overrides; it is refused when a
// channel of a material some face uses reaches 1 (the radiosity equation would have no solution).
#include <string>
#include <vector>

#include "core/types.h"
#include "mesh/mesh.h"

namespace radwalk {

struct MaterialOverride {
  std::string material;  // name as in newmtl (PLY: the generated colour names)
  std::string property;  // "Kd", "Ke", or "emissivity", "temperature", "heat_flux" (value[0])
  Rgb value = Rgb::Zero();
  std::string text;      // as given, for messages
};

// The heat-exchange properties (emissivity, temperature, heat_flux: one number each, radwalk exchange only). A
// temperature override drops the material's heat flux and a heat_flux override its temperature (a surface has one
// condition).
bool is_thermal_property(const std::string& property);

// "NAME.PROP=v" or "NAME.PROP=r,g,b". Throws InputError naming the text for a missing '.' or '=', a property
// other than Kd and Ke (with did-you-mean), a number that is not finite or a count other than 1 or 3, a Kd
// outside [0, 1) or a negative Ke. The material is looked up by apply_material_overrides.
MaterialOverride parse_material_override(const std::string& text);

// Applies the overrides in order (a later one for the same property wins), then multiplies every Kd by
// rho_scale (>= 0, finite). Throws InputError for an override naming a material the scene does not define
// (with did-you-mean and the scene's material names) and for a scaled Kd that reaches 1 on a material some face
// uses. Call between reading and validate_mesh.
void apply_material_overrides(Mesh& mesh, const std::vector<MaterialOverride>& overrides, double rho_scale = 1);

}  // namespace radwalk
