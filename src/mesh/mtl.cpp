#include "mesh/mtl.h"

#include <cmath>

#include "core/error.h"
#include "core/excerpt.h"
#include "mesh/text_scan.h"

namespace radwalk {

namespace {

// One number of statement `key`: NaN and infinity are refused here, for every statement (no later check sees
// Ks, Ni, Ns, Pr or Pm).
double finite_number(std::string_view token, const std::string& key, const std::string& path, long line) {
  const ParsedNumber n = parse_number(token);
  if (n.status == NumberStatus::ok && std::isfinite(n.value)) return n.value;
  const char* what = n.status == NumberStatus::out_of_range ? "out of range"
                     : n.status == NumberStatus::ok         ? "not a finite number"
                                                            : "not a number";
  std::string message = key;
  message.append(": '").append(excerpt(token)).append("' is ").append(what);
  throw InputError(locate(path, line, -1, message));
}

// "Kd r g b" or "Kd v": the colour after the keyword.
Rgb parse_colour(const std::vector<std::string_view>& tokens, const std::string& path, long line) {
  const std::string key(tokens[0]);
  if (tokens.size() >= 2 && (tokens[1] == "spectral" || tokens[1] == "xyz"))
    throw InputError(locate(path, line, -1, key + " " + excerpt(tokens[1]) + " is not supported: give r g b"));
  if (tokens.size() != 2 && tokens.size() != 4)
    throw InputError(locate(path, line, -1, key + " needs 1 or 3 numbers, found " +
                                                std::to_string(tokens.size() - 1)));
  Rgb c;
  for (std::size_t k = 1; k < tokens.size(); ++k) {
    c[static_cast<int>(k - 1)] = finite_number(tokens[k], key, path, line);
  }
  if (tokens.size() == 2) c = Rgb::Constant(c[0]);
  return c;
}

double parse_scalar(const std::vector<std::string_view>& tokens, const std::string& path, long line) {
  const std::string key(tokens[0]);
  if (tokens.size() != 2)
    throw InputError(locate(path, line, -1, key + " needs 1 number, found " + std::to_string(tokens.size() - 1)));
  return finite_number(tokens[1], key, path, line);
}

}  // namespace

std::vector<MtlEntry> scan_mtl(const std::string& path) { return scan_mtl_text(path, read_input_file(path)); }

std::vector<MtlEntry> scan_mtl_text(const std::string& path, std::string_view text) {
  std::vector<MtlEntry> entries;
  for_each_line(text, [&](long line, std::string_view content) {
    const auto tokens = split_tokens(content);
    if (tokens.empty()) return;
    const std::string_view key = tokens[0];
    if (key == "newmtl") {
      if (tokens.size() < 2) throw InputError(locate(path, line, -1, "newmtl without a name"));
      MtlEntry e;
      e.name = std::string(rest_of_statement(content, tokens[1]));  // the name rule of text_scan.h
      e.file = path;
      e.line = line;
      entries.push_back(std::move(e));
      return;
    }
    if (key == "map_Kd" && !entries.empty()) {
      // Skip the options and their values: the option words take 1 value, -mm 2, -o -s -t up to 3 numbers.
      std::size_t k = 1;
      while (k < tokens.size() && tokens[k].size() > 1 && tokens[k][0] == '-') {
        const std::string_view option = tokens[k++];
        const std::size_t most = option == "-mm" ? 2 : (option == "-o" || option == "-s" || option == "-t") ? 3 : 1;
        for (std::size_t v = 0; v < most && k < tokens.size(); ++v) {
          const bool number = parse_number(tokens[k]).status == NumberStatus::ok;
          if (most == 3 && !number) break;  // -o u [v [w]]: only numbers
          ++k;
        }
      }
      if (k < tokens.size()) {
        entries.back().map_Kd = std::string(rest_of_statement(content, tokens[k]));
        entries.back().map_Kd_line = line;
      }
      return;
    }
    const bool known = key == "Kd" || key == "Ke" || key == "Ks" || key == "illum" || key == "Ni" || key == "Ns" ||
                       key == "Pr" || key == "Pm" || key == kTwoSidedStatement || key == kEmissivityStatement ||
                       key == kTemperatureStatement || key == kHeatFluxStatement;
    if (!known) return;
    if (entries.empty())
      throw InputError(locate(path, line, -1, std::string(key) + " before the first newmtl statement"));
    MtlEntry& e = entries.back();
    if (key == "Kd") e.Kd = parse_colour(tokens, path, line);
    else if (key == "Ke") e.Ke = parse_colour(tokens, path, line);
    else if (key == "Ks") e.Ks = parse_colour(tokens, path, line);
    else if (key == "Ni") e.Ni = parse_scalar(tokens, path, line);
    else if (key == "Ns") e.Ns = parse_scalar(tokens, path, line);
    else if (key == kEmissivityStatement) {
      e.emissivity = parse_scalar(tokens, path, line);
      if (!(*e.emissivity > 0 && *e.emissivity <= 1))
        throw InputError(locate(path, line, -1, std::string(kEmissivityStatement) + " must be in (0, 1], found " +
                                                    excerpt(tokens[1])));
    } else if (key == kTemperatureStatement) {
      e.temperature = parse_scalar(tokens, path, line);
      if (!(*e.temperature >= 0 && *e.temperature <= 1e6))
        throw InputError(locate(path, line, -1, std::string(kTemperatureStatement) +
                                                    " must be a temperature in kelvin in [0, 1e6], found " +
                                                    excerpt(tokens[1])));
    } else if (key == kHeatFluxStatement) {
      e.heat_flux = parse_scalar(tokens, path, line);
      if (!(std::abs(*e.heat_flux) <= 1e12))
        throw InputError(locate(path, line, -1, std::string(kHeatFluxStatement) +
                                                    " must be a heat flux in W/m^2 of magnitude <= 1e12, found " +
                                                    excerpt(tokens[1])));
    }
    else if (key == "Pr") {
      e.Pr = parse_scalar(tokens, path, line);
      if (!(*e.Pr >= 0 && *e.Pr <= 1))  // the roughness Pr^2 is a GGX alpha (and 1e300^2 is no number)
        throw InputError(
            locate(path, line, -1, "Pr (roughness) must be in [0, 1], found " + excerpt(tokens[1])));
    } else if (key == "Pm") {
      e.Pm = parse_scalar(tokens, path, line);
    } else if (key == kTwoSidedStatement) {
      const auto v = tokens.size() == 2 ? parse_integral(tokens[1]) : std::nullopt;  // 0 or 1
      if (!v || (*v != 0 && *v != 1))
        throw InputError(locate(path, line, -1, std::string(kTwoSidedStatement) + " needs 0 or 1"));
      e.two_sided = *v == 1;
    } else {
      const auto v = tokens.size() == 2 ? parse_integral(tokens[1]) : std::nullopt;  // "2" or "2.0"
      if (!v || *v < 0 || *v > 10) throw InputError(locate(path, line, -1, "illum needs one integer in 0..10"));
      e.illum = static_cast<int>(*v);
    }
  });
  return entries;
}

Material material_from_mtl(const MtlEntry& e) {
  Material m;
  m.name = e.name;
  m.file = e.file;
  m.line = e.line;
  if (e.Kd) m.Kd = *e.Kd;
  if (e.Ke) m.Ke = *e.Ke;
  if (e.Ks) m.Ks = *e.Ks;
  if (e.Ni) m.Ni = *e.Ni;
  m.illum = e.illum.value_or(-1);
  m.two_sided = e.two_sided.value_or(false);
  m.emissivity = e.emissivity;
  m.temperature = e.temperature;
  m.heat_flux = e.heat_flux;
  m.metallic = e.Pm.value_or(0.0);
  const double Pr = e.Pr.value_or(0.0);

  // Kind: first matching rule of the table in mtl.h.
  const int illum = m.illum;
  if (illum == 4 || illum == 6 || illum == 7) m.kind = BsdfKind::dielectric;
  else if (m.metallic > 0) m.kind = BsdfKind::conductor;
  else if (illum == 3 || illum == 5) m.kind = Pr > 0 ? BsdfKind::microfacet : BsdfKind::mirror;
  else m.kind = BsdfKind::diffuse;

  // Roughness as GGX alpha.
  if (e.Pr) m.roughness = Pr * Pr;
  else if (m.kind == BsdfKind::conductor && e.Ns && *e.Ns >= 0) m.roughness = std::sqrt(2.0 / (*e.Ns + 2.0));
  return m;
}

}  // namespace radwalk
