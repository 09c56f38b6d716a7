#include "apps/power_balance.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "apps/pipeline.h"
#include "core/parallel.h"
#include "formfactor/form_factors.h"
#include "visibility/embree_visibility.h"

namespace radwalk::app {

RayFates trace_ray_fates(const PatchSet& patches, std::uint64_t seed, long rays, std::size_t max_patches) {
  RayFates fates;
  if (patches.size() == 0 || patches.size() > max_patches) return fates;
  const EmbreeVisibility visibility(patches);
  FormFactorOptions o;
  o.rays_per_patch = rays;
  o.seed = seed;
  // Row by row with the form factors' own rays (the same counts as estimate_form_factors gives), keeping only the
  // counts: no F is assembled, so the memory stays O(N).
  const std::size_t n = patches.size();
  fates.rays.resize(n);
  fates.escaped.resize(n);
  fates.back_hits.resize(n);
  parallel_for(n, [&](std::size_t i) {
    const FormFactorRow row = trace_form_factor_row(patches, visibility, o, i);
    fates.rays[i] = row.rays;
    fates.escaped[i] = row.escaped;
    fates.back_hits[i] = row.back_hits;
  });
  return fates;
}

void report_power_balance(const PatchSet& patches, const PatchRgb& B, const PatchRgb& B_se, const RayFates& fates,
                          RunSummary& summary) {
  // Powers in units of the largest emission s (E near the largest double squares to infinity otherwise).
  const double s = patches.max_emission();
  double emitted = 0;  // / s
  if (s > 0)
    for (std::size_t i = 0; i < patches.size(); ++i) emitted += patches.area[i] * (patches.E[i].mean() / s);
  nlohmann::json& j = summary.json()["power_balance"];
  j = {{"emitted", 1.0}};
  if (std::isfinite(emitted * s)) j["emitted_power"] = emitted * s;
  if (!(emitted > 0)) {
    j["note"] = "no emitted power";
    return;
  }
  if (fates.rays.size() != patches.size() || B.rows() != static_cast<Eigen::Index>(patches.size())) {
    j["absorbed"] = nullptr;
    j["escaped"] = nullptr;
    j["lost_to_back_faces"] = nullptr;
    j["note"] = "form factors read from a file carry no ray counts, or the scene is too large for the balance's rays";
    return;
  }
  double escaped = 0, back = 0, var_escaped = 0, var_back = 0;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const auto r = static_cast<Eigen::Index>(i);
    const double W = patches.area[i] * (B.row(r).mean() / s) / emitted;  // a fraction of the emitted power
    const double n = std::max<double>(fates.rays[i], 1);
    const double q = fates.escaped[i] / n, b = fates.back_hits[i] / n;
    escaped += W * q;
    back += W * b;
    var_escaped += W * W * q * (1 - q) / n;
    var_back += W * W * b * (1 - b) / n;
    if (B_se.rows() == B.rows()) {
      const double se = patches.area[i] * (B_se.row(r).mean() / s) / emitted;
      var_escaped += se * se * q * q;
      var_back += se * se * b * b;
    }
  }
  const double f_escaped = escaped, f_back = back;
  const double se_escaped = std::sqrt(var_escaped), se_back = std::sqrt(var_back);
  j["escaped"] = f_escaped;
  j["escaped_se"] = se_escaped;
  j["lost_to_back_faces"] = f_back;
  j["lost_to_back_faces_se"] = se_back;
  j["absorbed"] = 1 - f_escaped - f_back;
  j["absorbed_se"] = std::sqrt(se_escaped * se_escaped + se_back * se_back);
  char line[320];
  std::snprintf(line, sizeof line,
                "power balance: of the emitted power %.6g W, %.3g %% (+- %.2g) absorbed by the fronts of faces, "
                "%.3g %% (+- %.2g) escaped, %.3g %% (+- %.2g) lost into the backs of one-sided faces",
                emitted * s, 100 * (1 - f_escaped - f_back), 100 * j["absorbed_se"].get<double>(), 100 * f_escaped,
                100 * se_escaped, 100 * f_back, 100 * se_back);
  note(line);
  if (f_back > 0.01) {
    std::snprintf(line, sizeof line, "%.3g %% (+- %.2g) of the emitted power is lost into the backs of one-sided faces",
                  100 * f_back, 100 * se_back);
    warn(summary, std::string(line) +
                      ": faces oriented the wrong way (an inside-out room; --orient outward turns closed shells) or "
                      "open and thin parts whose backs the light reaches (make them two-sided: --open-shells two-sided, 'radwalk_two_sided 1' "
                      "or --two-sided); power_balance and the back_hits field say where");
  }
}

}  // namespace radwalk::app
