#pragma once
// MTL material libraries: the statements radwalk reads, and their mapping to a Material.
//
// Statements read (others are ignored): newmtl NAME (the rest of the statement, spaces included: the name
// rule of text_scan.h); Kd, Ke, Ks as "r g b" or a single "v" (g = b = v); illum N (an integer, "2.0"
// allowed); Ni, Ns, Pr, Pm as one number (Pr, perceptual roughness, in [0, 1]). Every number must be finite.
// Kd is the diffuse reflectance rho, Ke the emitted radiance L_e (so the emitted radiosity is E = pi * Ke).
// Numbers are read exactly (correctly rounded, see text_scan.h).
// radwalk's own statement: `radwalk_two_sided 1` (or 0, the default) makes the material's faces two-sided, a
// front and a back patch each (patch/patch_set.h; docs/two-sided.md). Other programs ignore it.
//
// Textures: `map_Kd [-options] FILE` names a texture multiplied by Kd (Kd 1 when the block has no Kd, as modelling
// tools write it). The radiosity solvers take one rho per material, so read_obj replaces Kd by Kd times the
// texture's mean linear colour (texture_mean.h), with a warning saying so; without a readable texture (missing,
// or neither PNG nor JPEG), by Kd times 0.5, the reflectance radwalk gives a face without material, with a warning
// naming the texture and `--set NAME.Kd=r,g,b` (docs/units-and-formats.md, "Materials"). The option words before the
// file name (-blendu, -blendv, -bm, -boost, -cc, -clamp, -imfchan, -mm, -o, -s, -t, -texres) and their values are
// skipped; the rest of the statement is the file name (spaces included), relative to the MTL file's directory.
//
// BsdfKind mapping (for the path tracer; the radiosity solvers use only Kd and Ke), first rule that applies:
//   illum 4, 6 or 7 (refraction)              -> dielectric (Ni = index of refraction)
//   Pm > 0                                    -> conductor  (Ks = F0 tint)
//   illum 3 or 5 (ray-traced reflection)      -> microfacet if Pr > 0, else mirror (Ks = tint)
//   anything else                             -> diffuse
// Roughness (GGX alpha): Pr^2 when Pr is given (Pr is perceptual roughness); otherwise, for a conductor with
// Ns, the Blinn-Phong equivalent sqrt(2 / (Ns + 2)) (Walter et al. 2007); otherwise 0.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/types.h"
#include "mesh/material.h"

namespace radwalk {

// One `newmtl` block as written in the file; every statement is optional.
struct MtlEntry {
  std::string name;
  std::string file;  // the MTL file
  long line = 0;     // line of the newmtl statement
  std::optional<Rgb> Kd, Ke, Ks;
  std::optional<int> illum;
  std::optional<double> Ni, Ns, Pr, Pm;
  std::optional<bool> two_sided;  // radwalk_two_sided 0|1
  // The grey-body heat-exchange keys (radwalk exchange, docs/heat-exchange.md): radwalk_emissivity E,
  // radwalk_temperature T (K), radwalk_heat_flux q (W/m^2, net leaving); other programs ignore them.
  std::optional<double> emissivity, temperature, heat_flux;
  std::optional<std::string> map_Kd;  // the texture file of map_Kd as written (options such as -s u v w skipped)
  long map_Kd_line = 0;
};

// The MTL statement that makes a material two-sided.
inline constexpr const char* kTwoSidedStatement = "radwalk_two_sided";
// The MTL statements of the heat-exchange keys.
inline constexpr const char* kEmissivityStatement = "radwalk_emissivity";
inline constexpr const char* kTemperatureStatement = "radwalk_temperature";
inline constexpr const char* kHeatFluxStatement = "radwalk_heat_flux";

// All newmtl blocks of an MTL file, in file order. Throws InputError naming file and line for a statement
// radwalk cannot read (a number that does not parse, is out of range or not finite, a spectral or xyz colour,
// a statement before the first newmtl).
std::vector<MtlEntry> scan_mtl(const std::string& path);
// The same for the bytes of an MTL file already read (path names it in messages).
std::vector<MtlEntry> scan_mtl_text(const std::string& path, std::string_view text);

// The Material for an entry, with the kind and roughness mapping above. Missing Kd and Ke stay zero.
Material material_from_mtl(const MtlEntry& entry);

}  // namespace radwalk
