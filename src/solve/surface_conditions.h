#pragma once
// The thermal condition of every patch from its material (mesh/material.h: Material::emissivity, temperature,
// heat_flux, from the MTL keys radwalk_emissivity, radwalk_temperature, radwalk_heat_flux or --set).
#include <vector>

#include "patch/patch_set.h"
#include "solve/net_radiation.h"

namespace radwalk {

// "file:line: material 'm'", or "material 'm'" when it comes from no file.
std::string material_where(const Material& m);

// Every material some patch uses must give an emissivity and exactly one of temperature and heat flux: otherwise
// one InputError naming the first such material (file, line) and the MTL statement or --set that fixes it, and
// the count of the others.
std::vector<SurfaceCondition> surface_conditions(const PatchSet& patches);

}  // namespace radwalk
