#include "mesh/material_override.h"

#include <algorithm>
#include <cmath>

#include "core/did_you_mean.h"
#include "core/error.h"
#include "mesh/text_scan.h"

namespace radwalk {

namespace {

std::string colour_text(const Rgb& c) {
  return number_text(c[0]) + "," + number_text(c[1]) + "," + number_text(c[2]);
}

}  // namespace

bool is_thermal_property(const std::string& property) {
  return property == "emissivity" || property == "temperature" || property == "heat_flux";
}

MaterialOverride parse_material_override(const std::string& text) {
  const std::string where = "--set '" + printable(text) + "': ";
  const std::string::size_type eq = text.find('=');
  if (eq == std::string::npos)
    throw InputError(where + "expected MATERIAL.Kd=r,g,b or MATERIAL.Ke=r,g,b (no '=')");
  const std::string::size_type dot = text.rfind('.', eq);
  if (dot == std::string::npos || dot == 0)
    throw InputError(where + "expected MATERIAL.Kd=r,g,b or MATERIAL.Ke=r,g,b (no material name before '.')");
  MaterialOverride o;
  o.text = text;
  o.material = text.substr(0, dot);
  o.property = text.substr(dot + 1, eq - dot - 1);
  if (o.property != "Kd" && o.property != "Ke" && !is_thermal_property(o.property))
    throw InputError(where + "unknown property '" + printable(o.property) + "'" +
                     did_you_mean(o.property, {"Kd", "Ke", "emissivity", "temperature", "heat_flux"}) +
                     "; --set changes Kd (rho) or Ke (emitted radiance), and for radwalk exchange emissivity, "
                     "temperature (K) or heat_flux (W/m^2)");
  std::vector<double> values;
  const std::string list = text.substr(eq + 1);
  std::string::size_type start = 0;
  while (true) {
    const std::string::size_type comma = list.find(',', start);
    const std::string token = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    const ParsedNumber n = parse_number(token);
    if (n.status != NumberStatus::ok || !std::isfinite(n.value))
      throw InputError(where + o.property + ": '" + printable(token) + "' is " +
                       (n.status == NumberStatus::out_of_range ? "out of range" : "not a finite number"));
    values.push_back(n.value);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (is_thermal_property(o.property) && values.size() != 1)
    throw InputError(where + o.property + " needs 1 number, found " + std::to_string(values.size()));
  if (o.property == "emissivity" && !(values[0] > 0 && values[0] <= 1))
    throw InputError(where + "emissivity " + number_text(values[0]) + " out of range: it must be in (0, 1]");
  if (o.property == "temperature" && !(values[0] >= 0 && values[0] <= 1e6))
    throw InputError(where + "temperature " + number_text(values[0]) + " out of range: kelvin in [0, 1e6]");
  if (o.property == "heat_flux" && !(std::abs(values[0]) <= 1e12))
    throw InputError(where + "heat_flux " + number_text(values[0]) + " out of range: W/m^2 of magnitude <= 1e12");
  if (values.size() != 1 && values.size() != 3)
    throw InputError(where + o.property + " needs 1 or 3 numbers, found " + std::to_string(values.size()));
  o.value = values.size() == 1 ? Rgb::Constant(values[0]) : Rgb(values[0], values[1], values[2]);
  if (o.property == "Kd" && !((o.value >= 0).all() && (o.value < 1).all()))
    throw InputError(where + "Kd " + colour_text(o.value) + " out of range: rho must be in [0, 1)");
  if (o.property == "Ke" && !((o.value >= 0).all() && (o.value <= 1e300).all()))
    throw InputError(where + "Ke " + colour_text(o.value) + " out of range: emitted radiance must be in [0, 1e300]");
  return o;
}

void apply_material_overrides(Mesh& mesh, const std::vector<MaterialOverride>& overrides, double rho_scale) {
  std::vector<std::string> names;
  for (const Material& m : mesh.materials) names.push_back(m.name);
  for (const MaterialOverride& o : overrides) {
    bool found = false;
    for (Material& m : mesh.materials)
      if (m.name == o.material) {
        if (o.property == "emissivity") {
          m.emissivity = o.value[0];
          m.reflectance_missing = false;  // the exchange's reflectance is 1 - emissivity
        } else if (o.property == "temperature") {
          m.temperature = o.value[0];
          m.heat_flux.reset();  // a later condition replaces an earlier one (or the file's)
        } else if (o.property == "heat_flux") {
          m.heat_flux = o.value[0];
          m.temperature.reset();
        } else {
          (o.property == "Kd" ? m.Kd : m.Ke) = o.value;
          if (o.property == "Kd") m.reflectance_missing = false;
        }
        found = true;
      }
    if (found) continue;
    std::string listed;
    for (std::size_t k = 0; k < names.size() && k < 20; ++k) listed += (k ? ", " : "") + ("'" + names[k] + "'");
    if (names.size() > 20) listed += ", ...";
    throw InputError("--set '" + printable(o.text) + "': " + mesh.path + " has no material '" +
                     printable(o.material) + "'" + did_you_mean(o.material, names) +
                     (names.empty() ? " (it has no materials)" : " (it has " + printable(listed) + ")"));
  }
  if (!(rho_scale >= 0 && std::isfinite(rho_scale)))
    throw InputError("--rho-scale " + number_text(rho_scale) + ": expected a finite number >= 0");
  if (rho_scale == 1) return;
  std::vector<bool> used(mesh.materials.size(), false);
  for (const std::int32_t m : mesh.face_material)
    if (m >= 0 && static_cast<std::size_t>(m) < used.size()) used[static_cast<std::size_t>(m)] = true;
  double brightest = 0;  // the largest Kd channel of a used material
  for (std::size_t i = 0; i < mesh.materials.size(); ++i)
    if (used[i]) brightest = std::max(brightest, mesh.materials[i].Kd.maxCoeff());
  for (std::size_t i = 0; i < mesh.materials.size(); ++i) {
    Material& m = mesh.materials[i];
    const Rgb scaled = m.Kd * rho_scale;
    if (used[i] && !(scaled < 1).all())
      throw InputError("--rho-scale " + number_text(rho_scale) + ": material '" + printable(m.name) + "' has Kd " +
                       colour_text(m.Kd) + ", scaled to " + colour_text(scaled) +
                       ", which reaches 1 (rho must stay below 1); this scene allows scales below " +
                       number_text(1 / brightest));
    m.Kd = scaled;
  }
}

}  // namespace radwalk
