#pragma once
// A surface material as read from MTL (or PLY face colours).
//
// Units and meanings: Kd is the diffuse reflectance rho per channel, in [0, 1); Ke is the emitted radiance L_e
// (W / (m^2 sr) in the mesh's length unit), so the emitted radiosity (exitance) of a Lambertian emitter is
// E = pi * Ke. The radiosity solvers use only Kd and Ke; the other fields serve the path tracer's images.
#include <optional>
#include <string>

#include "core/types.h"

namespace radwalk {

enum class BsdfKind { diffuse, mirror, dielectric, conductor, microfacet };

struct Material {
  std::string name;
  Rgb Kd = Rgb::Zero();  // diffuse reflectance rho
  Rgb Ke = Rgb::Zero();  // emitted radiance L_e
  BsdfKind kind = BsdfKind::diffuse;
  int illum = -1;        // MTL illumination model, -1 if absent
  Rgb Ks = Rgb::Zero();  // specular colour (mirror tint, conductor F0 or tint)
  double Ni = 1.5;       // index of refraction (dielectric)
  double roughness = 0;  // GGX alpha, from Pr or derived from Ns
  double metallic = 0;   // Pm
  bool two_sided = false;  // radwalk_two_sided 1: faces have a front and a back patch (patch/patch_set.h)
  // Grey-body heat exchange (radwalk exchange, solve/net_radiation.h): the hemispherical emissivity in (0, 1] and
  // either the temperature in kelvin or the net heat flux leaving the surface in W/m^2 (MTL radwalk_emissivity,
  // radwalk_temperature, radwalk_heat_flux; --set NAME.emissivity=, .temperature=, .heat_flux=). Unset when the
  // file does not give them; only `radwalk exchange` reads them.
  std::optional<double> emissivity, temperature, heat_flux;
  // The file names this material but gives it no reflectance (an STL solid, a VTK surface without a rho field):
  // validate_mesh refuses a face that uses it until `--set NAME.Kd=r,g,b` gives one (material_override.h).
  bool reflectance_missing = false;
  std::string texture;   // map_Kd texture file (resolved path) whose mean colour Kd includes, "" if none
  long line = 0;         // line in the MTL file where it is defined (0 if none)
  std::string file;      // MTL file where it is defined (empty if none)
};

}  // namespace radwalk
