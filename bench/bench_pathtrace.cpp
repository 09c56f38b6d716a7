// bench_pathtrace: path tracer throughput on the Cornell box (meshes/cornell_box.obj, one patch per input face,
// EmbreeVisibility), 256 x 256 pixels, MIS integrator, with 1 thread and all threads:
//   samples/s  camera samples (paths) per second,
//   rays/s     all rays traced (camera, continuation, shadow) per second,
//   patch averages with the same budget of paths (estimate_patch_averages) for comparison;
// then RMS error against time: patch averages of each integrator at 16, 64, ... --ref-spp / 16 samples per patch
// against a long MIS reference (--ref-spp samples per patch, default 65536), all threads. Error = area-weighted
// RMS over patches and channels of (B - B_ref), relative to the area-weighted RMS of B_ref; the reference's own
// noise is printed beside it.
// Writes the all-threads image as PNG (and EXR mean + standard error) when --out PREFIX is given.
// Usage: bench_pathtrace [--spp N] [--ref-spp N] [--scene PATH] [--out PREFIX]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

#include "bench_scene.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "io/exr_writer.h"
#include "io/png_writer.h"
#include "mesh/read_scene.h"
#include "patch/patching.h"
#include "pathtrace/patch_average.h"
#include "pathtrace/render.h"
#include "visibility/embree_visibility.h"

using namespace radwalk;

int main(int argc, char** argv) {
  long spp = 16;
  std::string scene = bench::default_scene();
  std::string out;
  long ref_spp = 65536;
  for (int k = 1; k < argc; ++k) {
    if (!std::strcmp(argv[k], "--spp") && k + 1 < argc) spp = std::atol(argv[++k]);
    else if (!std::strcmp(argv[k], "--scene") && k + 1 < argc) scene = argv[++k];
    else if (!std::strcmp(argv[k], "--out") && k + 1 < argc) out = argv[++k];
    else if (!std::strcmp(argv[k], "--ref-spp") && k + 1 < argc) ref_spp = std::atol(argv[++k]);
    else {
      std::fprintf(stderr, "usage: bench_pathtrace [--spp N] [--ref-spp N] [--scene PATH] [--out PREFIX]\n");
      return 2;
    }
  }
  if (!std::filesystem::exists(scene)) {
    std::printf("bench_pathtrace: %s not found, nothing to measure\n", scene.c_str());
    return 0;
  }
  Progress::set_enabled(false);
  const PatchSet patches = make_patches(load_scene(scene), 0);
  const EmbreeVisibility visibility(patches);
  RenderOptions o;
  o.width = 256;
  o.height = 256;
  o.spp = spp;
  o.progress = false;
  const Camera camera = Camera::cornell_box();
  std::printf("scene %s: %zu patches, %dx%d, %ld spp, integrator mis\n", scene.c_str(), patches.size(), o.width,
              o.height, spp);
  std::printf("%-8s %-14s %10s %14s %14s %12s\n", "threads", "what", "seconds", "samples/s", "Mrays/s", "rays/path");
  RenderResult last;
  for (int threads : {1, 0}) {
    const ThreadLimit limit(threads);
    const RenderResult r = render_image(patches, visibility, camera, o);
    const double paths = double(o.width) * o.height * spp;
    std::printf("%-8d %-14s %10.3f %14.0f %14.3f %12.2f\n", active_threads(), "render", r.seconds, paths / r.seconds,
                r.rays / r.seconds * 1e-6, r.rays / paths);
    PatchAverageOptions po;
    po.spp = static_cast<long>(paths / patches.size());
    po.progress = false;
    const Solution s = estimate_patch_averages(patches, visibility, po);
    std::printf("%-8d %-14s %10.3f %14.0f %14.3f %12.2f\n", active_threads(), "patch-average", s.seconds,
                double(s.walks) / s.seconds, s.info.at("rays") / s.seconds * 1e-6, s.info.at("rays") / double(s.walks));
    last = r;
  }
  std::printf("image mean radiance (r, g, b): %.4f %.4f %.4f\n", last.mean.mean()[0], last.mean.mean()[1],
              last.mean.mean()[2]);
  if (!out.empty()) {
    write_png(out + ".png", last.mean);
    write_exr(out + ".exr", last.mean);
    write_exr(out + "_se.exr", last.se);
    std::printf("wrote %s.png, %s.exr, %s_se.exr\n", out.c_str(), out.c_str(), out.c_str());
  }

  // RMS error of patch averages against a long reference, against time (all threads).
  PatchAverageOptions ro;
  ro.spp = ref_spp;
  ro.seed = 1000;
  ro.progress = false;
  const Solution ref = estimate_patch_averages(patches, visibility, ro);
  double ref_ms = 0, ref_noise = 0, area = 0;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    area += patches.area[i];
    for (int c = 0; c < 3; ++c) {
      ref_ms += patches.area[i] * ref.B(i, c) * ref.B(i, c);
      ref_noise += patches.area[i] * ref.B_se(i, c) * ref.B_se(i, c);
    }
  }
  std::printf("\nRMS error of patch averages against a MIS reference of %ld samples per patch (%.1f s; its own "
              "relative noise %.2e), all threads\n",
              ref_spp, ref.seconds, std::sqrt(ref_noise / ref_ms));
  std::printf("%-10s %10s %10s %14s\n", "integrator", "spp", "seconds", "rel RMS error");
  for (const IntegratorKind kind : {IntegratorKind::implicit, IntegratorKind::nee, IntegratorKind::mis}) {
    for (long n = 16; n <= ref_spp / 16; n *= 4) {
      PatchAverageOptions po;
      po.spp = n;
      po.seed = 7;
      po.progress = false;
      po.integrator.kind = kind;
      const Solution s = estimate_patch_averages(patches, visibility, po);
      double se = 0;
      for (std::size_t i = 0; i < patches.size(); ++i)
        for (int c = 0; c < 3; ++c) se += patches.area[i] * std::pow(s.B(i, c) - ref.B(i, c), 2);
      std::printf("%-10s %10ld %10.4f %14.3e\n", to_string(kind), n, s.seconds, std::sqrt(se / ref_ms));
    }
  }
  return 0;
}
