// radwalk pathtrace SCENE --spp N [--csv] [-o] [--image out.png|out.exr]: the continuous reference.
// Patch averages (same CSV columns and VTK fields as the solvers: B_*, B_se_*) and/or an image.
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "apps/options.h"
#include "apps/pipeline.h"
#include "core/error.h"
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

// The camera: --camera if given; the Cornell box's own camera for a scene named cornell_box*; otherwise a view
// of the bounding box from its -z side (40 degree vertical field of view).
Camera choose_camera(const PathtraceCommand& c, const PatchSet& patches) {
  if (c.camera.size() == 10) {
    Camera cam;
    cam.position = Vec3(c.camera[0], c.camera[1], c.camera[2]);
    cam.direction = Vec3(c.camera[3], c.camera[4], c.camera[5]) - cam.position;
    cam.up = Vec3(c.camera[6], c.camera[7], c.camera[8]);
    cam.vfov = c.camera[9] * kPi / 180.0;
    return cam;
  }
  if (std::filesystem::path(c.scene.scene).stem().string().rfind("cornell_box", 0) == 0) return Camera::cornell_box();
  Vec3 lo = patches.points[0], hi = patches.points[0];
  for (const Vec3& p : patches.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Vec3 center = 0.5 * (lo + hi);
  const double radius = 0.5 * (hi - lo).norm();
  Camera cam;
  cam.vfov = 40.0 * kPi / 180.0;
  cam.position = center - Vec3(0, 0, radius / std::tan(0.5 * cam.vfov) + 0.5 * (hi - lo).z());
  cam.direction = Vec3(0, 0, 1);
  cam.up = Vec3(0, 1, 0);
  return cam;
}

// path ends in .png or .exr (checked with the command line: apps/output_files.h).
void write_image(const std::string& path, const RenderResult& r) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".png") {
    write_png(path, r.mean);
  } else {
    write_exr(path, r.mean);
    const auto se = std::filesystem::path(path).replace_extension(".se.exr").string();
    write_exr(se, r.se);
    note("wrote " + se + " (per-pixel standard error)");
  }
  note("wrote " + path);
}

}  // namespace

int run_pathtrace(const PathtraceCommand& command) {
  if (!command.camera.empty() && command.camera.size() != 10)
    throw InputError("--camera takes 10 numbers: position (3), target (3), up (3), vertical fov in degrees");
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
    const Camera camera = choose_camera(command, patches);
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
                               {"spp", command.spp}, {"rays", r.rays}, {"seconds", r.seconds}};
    std::printf("rendered %dx%d at %ld samples per pixel: %ld rays in %.2f s (%.2f Mrays/s)\n", command.width,
                command.height, command.spp, r.rays, r.seconds, r.rays / std::max(r.seconds, 1e-9) / 1e6);
    write_image(command.image, r);
  }

  const bool averages = command.image.empty() || !command.scene.vtp.empty() || !command.scene.csv.empty();
  if (averages) {
    Solution s;
    if (light) {
      LightTraceOptions o;
      o.particles = command.spp * static_cast<long>(patches.size());
      o.seed = command.scene.seed;
      s = light_trace_patches(patches, visibility, o);
    } else {
      PatchAverageOptions o;
      o.spp = command.spp;
      o.seed = command.scene.seed;
      o.integrator = integrator;
      s = estimate_patch_averages(patches, visibility, o);
    }
    summary.add_timing("patch_averages", s.seconds);
    std::printf("%s: %s, %.2f s\n", s.method.c_str(), s.message.c_str(), s.seconds);
    summary.json()["solution"] = solution_json(s);
    std::vector<CellField> fields = {rgb_field("B", s.B), rgb_field("B_se", s.B_se)};
    if (s.var.size()) fields.push_back(rgb_field("var", s.var));
    write_outputs(command.scene, patches, fields, summary);
  } else if (!command.scene.json.empty()) {
    summary.write(command.scene.json);
  }
  return 0;
}

}  // namespace radwalk::app
