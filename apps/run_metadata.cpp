#include "apps/run_metadata.h"

#include <cmath>

#include "apps/pipeline.h"
#include "io/run_summary.h"

namespace radwalk::app {
namespace {

std::string command_line(const std::vector<std::string>& argv) {
  std::string line;
  for (const std::string& a : argv) {
    if (!line.empty()) line += ' ';
    const bool quote = a.empty() || a.find_first_of(" \t'\"$\\") != std::string::npos;
    if (!quote) {
      line += a;
      continue;
    }
    line += '\'';
    for (const char c : a) line += c == '\'' ? std::string("'\\''") : std::string(1, c);
    line += '\'';
  }
  return line;
}

std::string key_of(std::string stage) {
  for (char& c : stage)
    if (c == ' ' || c == '-') c = '_';
  return stage;
}

}  // namespace

std::string run_id(const SceneOptions& options, const Digest& input_bytes) {
  Digest d;
  d.add(std::string("radwalk ") + RADWALK_VERSION);
  d.add(std::string_view(git_describe()));
  d.add(options.run_options);
  d.add(input_bytes.value());
  return d.hex();
}

std::string run_id_of(RunSummary& summary) { return summary.json().value("run_id", std::string()); }

VtpMetadata run_metadata(const SceneOptions& options, RunSummary& summary) {
  const nlohmann::json& j = summary.json();
  VtpMetadata m;
  if (j.contains("run_id")) m.set_text("run_id", j["run_id"].get<std::string>());
  m.set_text("radwalk_version", j.value("radwalk_version", std::string("unknown")));
  m.set_text("git_commit", git_describe());  // the JSON summary's git_describe (io/run_summary.h)
  m.set_text("command", j.value("command", std::string()));
  m.set_text("command_line", command_line(options.argv));
  m.set_text("scene", options.scene);
  m.set_integer("seed", std::int64_t(options.seed));
  m.set_real("max_edge", options.max_edge);
  if (j.contains("patches")) m.set_integer("patches", j["patches"].get<std::int64_t>());
  const LengthUnit unit = length_unit(options);
  m.set_text("length_unit", unit.length() == "mesh unit" ? "the scene file's unit (the bundled Cornell box: mm)"
                                                         : unit.length());
  m.set_text("B_unit", unit.radiosity() + "; radiance = B / pi");
  m.set_text("B_srgb", "round(255 sRGB(clamp(B / pi, 0, 1))) per channel, exposure 1 (as the path tracer's PNG)");
  if (j.contains("rays_total")) m.set_integer("rays", std::llround(j["rays_total"].get<double>()));
  if (j.contains("form_factors_file")) m.set_text("form_factors_file", j["form_factors_file"].get<std::string>());
  if (j.contains("timings_s"))
    for (const auto& [stage, seconds] : j["timings_s"].items()) m.set_real("seconds_" + key_of(stage), seconds.get<double>());
  return m;
}

VtpMetadata solution_metadata(const Solution& s, const PatchSet& patches) {
  VtpMetadata m;
  m.set_text("method", s.method);
  m.set_text("status", to_string(s.status));
  if (s.iterations > 0) m.set_integer("iterations", s.iterations);
  if (std::isfinite(s.residual)) m.set_real("residual", s.residual);
  if (s.walks > 0) {
    m.set_integer("walks", s.walks);
    m.set_integer("steps", s.steps);
  }
  m.set_real("solve_seconds", s.seconds);
  if (s.B_se.rows() == s.B.rows() && s.B.rows() == static_cast<Eigen::Index>(patches.size())) {
    double max_se = 0, se2 = 0, b2 = 0;
    for (Eigen::Index i = 0; i < s.B.rows(); ++i)
      for (int c = 0; c < 3; ++c) {
        if (!std::isfinite(s.B_se(i, c))) continue;
        max_se = std::max(max_se, s.B_se(i, c));
        se2 += patches.area[i] * s.B_se(i, c) * s.B_se(i, c);
        b2 += patches.area[i] * s.B(i, c) * s.B(i, c);
      }
    m.set_real("B_se_max", max_se);
    if (b2 > 0) m.set_real("B_se_relative_rms", std::sqrt(se2 / b2));
  }
  return m;
}

nlohmann::json camera_json(const SceneCamera& fitted, const PatchSet& patches, int width, int height) {
  const Camera& c = fitted.camera;
  const Vec3 look_at = camera_focal_point(c, patches);
  const Vec3 d = c.direction.normalized();
  return {{"position", {c.position.x(), c.position.y(), c.position.z()}},
          {"look_at", {look_at.x(), look_at.y(), look_at.z()}},
          {"direction", {d.x(), d.y(), d.z()}},
          {"up", {c.up.x(), c.up.y(), c.up.z()}},
          {"vertical_fov_deg", c.vfov * 180.0 / kPi},
          {"width", width},
          {"height", height},
          {"source", fitted.source}};
}

nlohmann::json target_error_step_json(const TargetErrorStep& s) {
  return {{"patches", s.patches},
          {"rays_per_patch", s.rays_per_patch},
          {"statistical", s.statistical},
          {"discretisation", s.discretisation},
          {"total", s.total},
          {"seconds", s.seconds},
          {"split", s.split},
          {"next_rays_per_patch", s.next_rays_per_patch},
          {"groups", s.groups},
          {"groups_within", s.groups_within},
          {"worst_group", s.worst_group},
          {"worst_group_total", s.worst_group_total}};
}

nlohmann::json group_mean_errors_json(const std::vector<GroupMeanError>& groups) {
  nlohmann::json a = nlohmann::json::array();
  for (const GroupMeanError& g : groups) {
    if (!g.counted) continue;
    a.push_back({{"name", g.name},
                 {"area", g.area},
                 {"mean", g.mean},
                 {"estimate", g.estimate},
                 {"discretisation", g.discretisation},
                 {"statistical", g.statistical},
                 {"statistical_kind", g.statistical_kind},
                 {"statistical_bound", g.statistical_bound},
                 {"total", g.total}});
  }
  return a;
}

nlohmann::json refine_step_json(const RefineStep& s) {
  return {{"step", s.step},
          {"patches", s.patches},
          {"marked", s.marked},
          {"split", s.split},
          {"max_jump", s.max_jump},
          {"method", s.method},
          {"iterations", s.iterations},
          {"form_factor_seconds", s.form_factor_seconds},
          {"solve_seconds", s.solve_seconds},
          {"refine_seconds", s.refine_seconds},
          {"seconds", s.seconds}};
}

}  // namespace radwalk::app
