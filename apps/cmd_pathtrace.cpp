// radwalk pathtrace SCENE --spp N [--csv] [-o] [--image out.png|out.exr]: the continuous reference.
// Patch averages (same CSV columns and VTK fields as the solvers: B_*, B_se_*) and/or an image.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <utility>

#include "apps/finite_outputs.h"
#include "apps/options.h"
#include "apps/pipeline.h"
#include "apps/power_balance.h"
#include "apps/progressive_series.h"
#include "apps/run_metadata.h"
#include "apps/scene_camera.h"
#include "core/atomic_write.h"
#include "core/error.h"
#include "core/format_number.h"
#include "core/image.h"
#include "core/moments.h"
#include "core/parallel.h"
#include "core/timer.h"
#include "io/exr_writer.h"
#include "io/png_writer.h"
#include "pathtrace/camera.h"
#include "pathtrace/light_tracer.h"
#include "pathtrace/patch_average.h"
#include "pathtrace/render.h"
#include "visibility/embree_visibility.h"

namespace radwalk::app {
namespace {

// path ends in .png or .exr (checked with the command line: apps/output_files.h).
void write_image(const std::string& path, const RenderResult& r, const std::string& run_id) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".png") {
    write_png(path, r.mean, 1.0, run_id);
  } else {
    write_exr(path, r.mean, ExrPixelType::float32, run_id);
    const auto se = std::filesystem::path(path).replace_extension(".se.exr").string();
    write_exr(se, r.se, ExrPixelType::float32, run_id);
    note("wrote " + se + " (per-pixel standard error)");
  }
  note("wrote " + path);
}

// The patches whose B_se cannot be trusted (core/moments.h: VOV above kVovReliable on some channel): counted in
// the JSON's solution.vov, and one note naming the worst. Such a patch's samples are ruled by a few rare bright
// paths: this run caught some, so its B_se is itself uncertain, and a run that misses them states too small an
// error there (docs/path-tracer.md, "How far to trust B_se"). A patch whose samples all agree has VOV 0.
void report_standard_error_reliability(const PatchSet& patches, const Solution& s, RunSummary& summary) {
  if (!s.vov.size()) return;
  long unreliable = 0;
  double worst = 0;
  Eigen::Index worst_row = -1;
  for (Eigen::Index r = 0; r < s.vov.rows(); ++r) {
    const double v = s.vov.row(r).maxCoeff();
    if (v > kVovReliable) ++unreliable;
    if (v > worst) worst = v, worst_row = r;
  }
  summary.json()["solution"]["vov"] = {{"reliable_below", kVovReliable},
                                       {"unreliable_patches", unreliable},
                                       {"max", worst},
                                       {"max_patch", worst_row}};
  if (unreliable == 0) return;
  const auto i = static_cast<std::size_t>(worst_row);
  std::string names;
  for (const auto& [kind, name] : {std::pair{"object", &patches.object_of(i)}, std::pair{"group", &patches.group_of(i)},
                                   std::pair{"material", &patches.material_of(i)}})
    if (!name->empty()) names += std::string(", ") + kind + " '" + *name + "'";
  note("path tracer: on " + std::to_string(unreliable) + " of " + std::to_string(patches.size()) +
       " patches the variance of the variance is above " + format_number(kVovReliable) + " (largest " +
       format_number(worst, 3) + ", patch " + std::to_string(worst_row) + ", input face " +
       std::to_string(patches.face[i]) + names + "): a few rare bright paths rule their samples, so their B_se is "
       "itself uncertain (field B_vov); more samples (--spp) settle it");
}

}  // namespace

int run_pathtrace(const PathtraceCommand& command) {
  if (!command.camera.empty() && command.camera.size() != 10)
    throw InputError("--camera takes 10 numbers: position (3), target (3), up (3), vertical fov in degrees");
  if (!command.image.empty())  // refused up front with the bytes the size would need (O4)
    check_image_size(command.width, command.height,
                     "--width " + std::to_string(command.width) + " --height " + std::to_string(command.height));
  RunSummary summary("pathtrace", command.scene.argv);
  const PatchSet patches = load_patches(command.scene, summary);
  ThreadLimit limit(command.scene.threads);
  Timer timer;
  const EmbreeVisibility visibility(patches);
  summary.add_timing("embree_scene", timer.seconds());
  const bool light = command.integrator == "light";
  IntegratorOptions integrator;
  if (!light) integrator.kind = parse_integrator_kind(command.integrator);

  if (!command.image.empty()) {
    const SceneCamera fitted = fit_scene_camera(command.scene.scene, patches, command.camera, &visibility);
    const Camera& camera = fitted.camera;
    const Vec3 look_at = camera_focal_point(camera, patches);
    summary.json()["camera"] = camera_json(fitted, patches, command.width, command.height);
    if (fitted.source == "inside" || fitted.source == "outside")
      note("camera " + fitted.source + " the scene (" + (fitted.source == "inside" ? "it is closed" : "it is open") +
           "), at " + number_text(camera.position.x()) + " " + number_text(camera.position.y()) + " " +
           number_text(camera.position.z()) + " looking at " + number_text(look_at.x()) + " " +
           number_text(look_at.y()) + " " + number_text(look_at.z()) + "; --camera sets another");
    RenderResult r;
    if (light) {
      LightTraceOptions o;
      o.particles = command.spp * command.width * command.height;
      o.seed = command.scene.seed;
      r = light_trace_image(patches, visibility, camera, command.width, command.height, o);
    } else {
      RenderOptions o;
      o.width = command.width;
      o.height = command.height;
      o.spp = command.spp;
      o.seed = command.scene.seed;
      o.integrator = integrator;
      r = render_image(patches, visibility, camera, o);
    }
    summary.add_timing("render", r.seconds);
    summary.json()["image"] = {{"file", command.image}, {"width", command.width}, {"height", command.height},
                               {"samples_per_pixel", command.spp}, {"rays_total", r.rays}, {"seconds", r.seconds}};
    std::fprintf(report_stream(), "rendered %dx%d at %ld samples per pixel: %ld rays in %.2f s (%.2f Mrays/s)\n", command.width,
                command.height, command.spp, r.rays, r.seconds, r.rays / std::max(r.seconds, 1e-9) / 1e6);
    if (std::all_of(r.mean.pixels.begin(), r.mean.pixels.end(), [](const Rgb& p) { return (p == 0).all(); }))
      warn(summary, "every pixel of " + command.image + " is black: the camera sees no lit surface (no emitter, " +
                        "or the camera is outside a closed scene or inside an object); set one with --camera");
    refuse_overflow(r.mean, r.se, command.image, patches.max_emission());
    write_image(command.image, r, run_id_of(summary));
  }

  const bool averages = command.image.empty() || !command.scene.vtp.empty() || !command.scene.csv.empty() ||
                        !command.progressive.empty();
  if (averages) {
    // Patch averages from spp samples per patch (light tracing: spp x N particles).
    const auto estimate = [&](long spp) {
      if (light) {
        LightTraceOptions o;
        o.particles = spp * static_cast<long>(patches.size());
        o.seed = command.scene.seed;
        return light_trace_patches(patches, visibility, o);
      }
      PatchAverageOptions o;
      o.spp = spp;
      o.seed = command.scene.seed;
      o.integrator = integrator;
      return estimate_patch_averages(patches, visibility, o);
    };
    const Solution s = estimate(command.spp);
    refuse_overflow(s, "pathtrace", patches.max_emission());
    summary.add_timing("patch_averages", s.seconds);
    if (!command.progressive.empty())
      write_convergence_series(command.progressive, "pathtrace.pvd", command.scene.scene, patches, command.spp, s,
                               estimate, summary);
    std::fprintf(report_stream(), "%s: %s, %.2f s\n", s.method.c_str(), s.message.c_str(), s.seconds);
    summary.json()["solution"] = solution_json(s);
    report_standard_error_reliability(patches, s, summary);
    report_power_balance(patches, s.B, s.B_se, trace_ray_fates(patches, command.scene.seed), summary);
    std::vector<CellField> fields = {rgb_field("B", s.B), rgb_field("B_se", s.B_se)};
    if (s.var.size()) fields.push_back(with_csv_name(rgb_field("B_var", s.var), "var"));  // CSV: var_*
    if (s.vov.size()) fields.push_back(with_csv_name(rgb_field("B_vov", s.vov), "vov"));  // CSV: vov_*
    VtpMetadata metadata = solution_metadata(s, patches);
    metadata.set_text("integrator", command.integrator);
    metadata.set_integer(light ? "particles_per_patch" : "spp", command.spp);
    write_outputs(command.scene, patches, fields, summary, metadata);
  } else if (!command.scene.json.empty()) {
    summary.write(command.scene.json);
  }
  return 0;
}

}  // namespace radwalk::app
