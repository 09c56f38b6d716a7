// radwalk.pathtrace: the continuous path tracer (patch averages with error bars, and images as float arrays).
#include <optional>

#include "apps/scene_camera.h"
#include "bindings.h"
#include "core/error.h"
#include "core/image.h"
#include "core/parallel.h"
#include "core/timer.h"
#include "interruptible.h"
#include "pathtrace/light_tracer.h"
#include "pathtrace/patch_average.h"
#include "pathtrace/render.h"
#include "visibility/embree_visibility.h"

namespace radwalk::python {
namespace {

struct PathtraceResult {
  std::optional<Result> averages;
  RenderResult image;
  bool has_image = false;
  std::map<std::string, double> timings;
};

// A (height, width, 3) float64 copy of an image.
py::array_t<double> image_array(const RgbImage& image) {
  py::array_t<double> a({py::ssize_t{image.height}, py::ssize_t{image.width}, py::ssize_t{3}});
  double* out = a.mutable_data();
  for (const Rgb& p : image.pixels)
    for (int c = 0; c < 3; ++c) *out++ = p[c];
  return a;
}

PathtraceResult pathtrace(const Scene& scene, long spp, const std::string& integrator_name, std::uint64_t seed,
                          bool averages, bool image, int width, int height, const std::vector<double>& camera_numbers,
                          long long threads_arg, bool progress) {
  const int threads = check_run(scene, threads_arg);
  if (!camera_numbers.empty() && camera_numbers.size() != 10)
    throw InputError("--camera takes 10 numbers: position (3), target (3), up (3), vertical fov in degrees");
  // Samples as the CLI's: from 2 (a standard error needs two) to 2^32, so spp x pixels and spp x N cannot overflow.
  if (spp < 2 || spp > (1L << 32))
    throw InputError("spp " + std::to_string(spp) + ": expected a whole number from 2 to 4294967296");
  if (image)  // the CLI's limit (core/image.h), before anything is traced
    check_image_size(width, height, "width=" + std::to_string(width) + ", height=" + std::to_string(height));
  const bool light = integrator_name == "light";
  IntegratorOptions integrator;
  if (!light) integrator.kind = parse_integrator_kind(integrator_name);
  PathtraceResult r;
  Solution s;
  interruptible([&] {
    ThreadLimit limit(threads);
    Timer timer;
    const EmbreeVisibility visibility(scene.patches);
    r.timings["embree_scene"] = timer.seconds();
    if (image) {
      const Camera camera = app::scene_camera(scene.path, scene.patches, camera_numbers);
      if (light) {
        LightTraceOptions o;
        o.particles = spp * width * height;
        o.seed = seed;
        o.progress = progress;
        r.image = light_trace_image(scene.patches, visibility, camera, width, height, o);
      } else {
        RenderOptions o;
        o.width = width;
        o.height = height;
        o.spp = spp;
        o.seed = seed;
        o.integrator = integrator;
        o.progress = progress;
        r.image = render_image(scene.patches, visibility, camera, o);
      }
      r.has_image = true;
      r.timings["render"] = r.image.seconds;
    }
    if (averages) {
      if (light) {
        LightTraceOptions o;
        o.particles = spp * static_cast<long>(scene.patches.size());
        o.seed = seed;
        o.progress = progress;
        s = light_trace_patches(scene.patches, visibility, o);
      } else {
        PatchAverageOptions o;
        o.spp = spp;
        o.seed = seed;
        o.integrator = integrator;
        o.progress = progress;
        s = estimate_patch_averages(scene.patches, visibility, o);
      }
      r.timings["patch_averages"] = s.seconds;
    }
  });
  if (averages) {
    Result a;
    a.solution = std::move(s);
    a.timings = r.timings;
    nlohmann::json run = {{"integrator", integrator_name}, {"seed", seed}, {"threads", threads}};
    run[light ? "particles_per_patch" : "spp"] = spp;
    a.metadata = result_metadata(a, scene, run);
    r.averages = std::move(a);
  }
  return r;
}

}  // namespace

void bind_pathtrace(py::module_& m) {
  py::class_<PathtraceResult>(m, "PathtraceResult", R"doc(What pathtrace() returns.

averages: a Result (B, B_se, var per patch) or None; image, image_se: (height, width, 3) float64 arrays of
radiance and its per-pixel standard error (copies), or None; rays, seconds: of the image; timings.)doc")
      .def_property_readonly(
          "averages", [](const PathtraceResult& r) { return r.averages; },
          "The patch averages as a Result (B, B_se, var (N, 3) float64, W per unit length "
          "squared), or None when averages=False.")
      .def_property_readonly(
          "image",
          [](const PathtraceResult& r) -> py::object {
            if (!r.has_image) return py::none();
            return image_array(r.image.mean);
          },
          "The image's radiance, (height, width, 3) float64 (a copy), W per unit length squared per sr; None "
          "without image=True.")
      .def_property_readonly(
          "image_se",
          [](const PathtraceResult& r) -> py::object {
            if (!r.has_image) return py::none();
            return image_array(r.image.se);
          },
          "The per-pixel standard error of image, (height, width, 3) float64 (a copy), in its unit; None without "
          "image=True.")
      .def_property_readonly(
          "rays", [](const PathtraceResult& r) { return r.image.rays; }, "Rays traced for the image (int).")
      .def_property_readonly(
          "seconds", [](const PathtraceResult& r) { return r.image.seconds; }, "Wall time of the image (float, s).")
      .def_readonly("timings", &PathtraceResult::timings, "Stage -> wall time (dict str -> float, s).");

  m.def("pathtrace", &pathtrace, py::arg("scene"), py::arg("spp") = 64, py::arg("integrator") = "mis",
        py::arg("seed") = 1, py::arg("averages") = true, py::arg("image") = false, py::arg("width") = 256,
        py::arg("height") = 256, py::arg("camera") = std::vector<double>{}, py::arg("threads") = 0,
        py::arg("progress") = false,
        R"doc(The continuous path tracer (no patches, no F): patch averages with error bars and/or an image.

As `radwalk pathtrace`: spp samples per patch (averages) and per pixel (image); integrator "mis", "nee",
"implicit" or "light" (light tracing: spp x N particles for the averages, spp x width x height for the image);
camera: 10 numbers, shape (10,) (position (3,) and target (3,) in mesh length units, up (3,), vertical fov in
degrees) or empty for the one camera rule (pathtrace's fit, apps/scene_camera.h: the Cornell camera for
cornell_box*, the objects of a closed room, else a view of the bounding box); width x height at most 2^26 pixels, as the CLI
(InputError before anything is traced). Returns a PathtraceResult; its averages are a Result (B (N, 3) float64,
W per unit length squared), its image a (height, width, 3) float64 radiance array.)doc");
}

}  // namespace radwalk::python
