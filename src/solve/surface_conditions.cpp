#include "solve/surface_conditions.h"

#include <string>

#include "core/error.h"

namespace radwalk {

std::string material_where(const Material& m) {
  return (m.file.empty() ? std::string() : m.file + ":" + std::to_string(m.line) + ": ") + "material '" + m.name + "'";
}

std::vector<SurfaceCondition> surface_conditions(const PatchSet& patches) {
  std::vector<bool> used(patches.materials.size(), false);
  for (std::int32_t m : patches.material)
    if (m >= 0) used[std::size_t(m)] = true;
  std::vector<std::string> problems;
  for (std::size_t k = 0; k < patches.materials.size(); ++k) {
    if (!used[k]) continue;
    const Material& m = patches.materials[k];
    if (!m.emissivity)
      problems.push_back(material_where(m) + " has no emissivity: add 'radwalk_emissivity E' (0 < E <= 1) to its "
                         "block or --set '" + m.name + ".emissivity=E'");
    if (!m.temperature && !m.heat_flux)
      problems.push_back(material_where(m) + " has neither a temperature nor a heat flux: add 'radwalk_temperature "
                         "T' (kelvin) or 'radwalk_heat_flux q' (W/m^2, net leaving; 0 for a re-radiating wall), or "
                         "--set '" + m.name + ".temperature=T'");
    if (m.temperature && m.heat_flux)
      problems.push_back(material_where(m) + " has both radwalk_temperature and radwalk_heat_flux: a surface has one "
                         "known and one solved; remove one (or --set one, which drops the other)");
  }
  if (!problems.empty())
    throw InputError(problems.front() + (problems.size() > 1 ? " (and " + std::to_string(problems.size() - 1) +
                                                                     " more such problem(s) in other materials)"
                                                               : std::string()));
  std::vector<SurfaceCondition> s(patches.size());
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const Material& m = patches.materials[std::size_t(patches.material[i])];
    s[i].emissivity = *m.emissivity;
    s[i].temperature_given = m.temperature.has_value();
    s[i].temperature = m.temperature.value_or(0.0);
    s[i].heat_flux = m.heat_flux.value_or(0.0);
  }
  return s;
}

}  // namespace radwalk
