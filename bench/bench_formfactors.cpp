// bench_formfactors: form-factor throughput against raw Embree on the Cornell box, and peak memory.
//
// For the Cornell box (meshes/cornell_box.obj patched by bench_scene.h to about 1,000,
// 10,000 and 100,000 patches), with 1 thread and all threads:
//   raw Embree   incoherent rays (random patch, uniform point, cosine direction, spawn_ray offset) traced with
//                rtcIntersect1 and rtcIntersect16 on an Embree scene built here with the same flags as
//                EmbreeVisibility (robust, isa=avx2); rays are generated beforehand (a buffer of up to 2^21 rays,
//                reused), so only tracing is timed; the faster call is timed again for the same number of rays as
//                the form-factor run;
//   form factors estimate_form_factors (sampling, tracing through EmbreeVisibility's batches, CSR assembly);
//   ratio        form-factor Mrays/s / best raw Embree Mrays/s (target >= 0.8 with all threads);
//   memory       peak resident memory of a fresh child process running the largest scene's form factors on all
//                threads (target: 100,000 patches x 1,000 rays under 2 GB).
// Usage: bench_formfactors [--quick] [--rays R] [--scene PATH]
#include <embree3/rtcore.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "bench_scene.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/timer.h"
#include "formfactor/form_factors.h"
#include "visibility/embree_visibility.h"

using namespace radwalk;

namespace {

// An Embree scene with the same content and flags as EmbreeVisibility, for timing raw rtcIntersect calls.
struct RawEmbree {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  explicit RawEmbree(const PatchSet& ps) {
    device = rtcNewDevice("isa=avx2");
    scene = rtcNewScene(device);
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    for (const bool quads : {false, true}) {
      std::vector<std::size_t> prims;
      for (std::size_t i = 0; i < ps.size(); ++i)
        if (ps.is_quad(i) == quads) prims.push_back(i);
      if (prims.empty()) continue;
      RTCGeometry g = rtcNewGeometry(device, quads ? RTC_GEOMETRY_TYPE_QUAD : RTC_GEOMETRY_TYPE_TRIANGLE);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                            3 * sizeof(float), ps.points.size()));
      for (std::size_t p = 0; p < ps.points.size(); ++p)
        for (int c = 0; c < 3; ++c) v[3 * p + c] = float(ps.points[p][c]);
      const int m = quads ? 4 : 3;
      auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
          g, RTC_BUFFER_TYPE_INDEX, 0, quads ? RTC_FORMAT_UINT4 : RTC_FORMAT_UINT3, m * sizeof(unsigned), prims.size()));
      for (std::size_t k = 0; k < prims.size(); ++k)
        for (int r = 0; r < m; ++r) idx[m * k + r] = unsigned(ps.corners[prims[k]][r]);
      rtcCommitGeometry(g);
      rtcAttachGeometry(scene, g);
      rtcReleaseGeometry(g);
    }
    rtcCommitScene(scene);
  }
  ~RawEmbree() {
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
  }
};

// bench::incoherent_rays in Embree's single-ray layout.
std::vector<RTCRay> make_rays(const PatchSet& ps, std::size_t n) {
  const std::vector<Ray> source = bench::incoherent_rays(ps, n, 99);
  std::vector<RTCRay> rays(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Ray& r = source[k];
    RTCRay& e = rays[k];
    e.org_x = float(r.origin.x()), e.org_y = float(r.origin.y()), e.org_z = float(r.origin.z());
    e.dir_x = float(r.direction.x()), e.dir_y = float(r.direction.y()), e.dir_z = float(r.direction.z());
    e.tnear = 0, e.tfar = INFINITY, e.time = 0, e.mask = ~0u, e.id = unsigned(k), e.flags = 0;
  }
  return rays;
}

// Mrays/s of tracing `total` rays (cycling through `rays`) with rtcIntersect1 or rtcIntersect16.
double raw_throughput(const RawEmbree& e, const std::vector<RTCRay>& rays, std::size_t total, bool packets) {
  std::vector<unsigned> sink((total + 4095) / 4096);
  Timer timer;
  parallel_chunks(total, 4096, [&](std::size_t b, std::size_t end) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    unsigned hits = 0;
    if (!packets) {
      RTCRayHit rh;
      for (std::size_t k = b; k < end; ++k) {
        rh.ray = rays[k % rays.size()];
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(e.scene, &ctx, &rh);
        hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
      }
    } else {
      RTCRayHit16 rh;
      int valid[16];
      for (std::size_t base = b; base < end; base += 16) {
        for (int l = 0; l < 16; ++l) {
          const std::size_t k = base + l;
          valid[l] = k < end ? -1 : 0;
          const RTCRay& r = rays[std::min(k, end - 1) % rays.size()];
          rh.ray.org_x[l] = r.org_x, rh.ray.org_y[l] = r.org_y, rh.ray.org_z[l] = r.org_z;
          rh.ray.dir_x[l] = r.dir_x, rh.ray.dir_y[l] = r.dir_y, rh.ray.dir_z[l] = r.dir_z;
          rh.ray.tnear[l] = 0, rh.ray.tfar[l] = INFINITY, rh.ray.time[l] = 0, rh.ray.mask[l] = ~0u;
          rh.ray.id[l] = unsigned(l), rh.ray.flags[l] = 0;
          rh.hit.geomID[l] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect16(valid, e.scene, &ctx, &rh);
        for (int l = 0; l < 16; ++l) hits += valid[l] && rh.hit.geomID[l] != RTC_INVALID_GEOMETRY_ID;
      }
    }
    sink[b / 4096] = hits;
  });
  return double(total) / timer.seconds() * 1e-6;
}

struct FormFactorRun {
  double mrays_per_s = 0, seconds = 0, peak_mb = 0, nnz = 0;
};

FormFactorRun run_form_factors(const PatchSet& ps, long rays) {
  const EmbreeVisibility vis(ps);
  FormFactorOptions opt;
  opt.rays_per_patch = rays;
  Timer timer;
  const FormFactors ff = estimate_form_factors(ps, vis, opt);
  FormFactorRun r;
  r.seconds = timer.seconds();
  r.mrays_per_s = double(ps.size()) * double(rays) / r.seconds * 1e-6;
  r.peak_mb = double(peak_memory_bytes()) / (1 << 20);
  r.nnz = double(ff.F.nonZeros());
  return r;
}

// The form-factor run of the largest scene in a fresh process, so its peak memory is its own.
FormFactorRun run_in_child(const std::string& scene, std::size_t target, long rays) {
  const std::string cmd = "/proc/" + std::to_string(::getpid()) + "/exe --child " + std::to_string(target) + " " +
                          std::to_string(rays) + " --scene '" + scene + "'";
  FormFactorRun r;
  if (FILE* p = ::popen(cmd.c_str(), "r")) {
    if (std::fscanf(p, "%lf %lf %lf %lf", &r.mrays_per_s, &r.seconds, &r.peak_mb, &r.nnz) != 4) r = {};
    ::pclose(p);
  }
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  long rays = 1000;
  std::string scene = bench::default_scene();
  long child_target = -1;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--quick") quick = true;
    else if (arg == "--rays" && a + 1 < argc) rays = std::atol(argv[++a]);
    else if (arg == "--scene" && a + 1 < argc) scene = argv[++a];
    else if (arg == "--child" && a + 2 < argc) {
      child_target = std::atol(argv[++a]);
      rays = std::atol(argv[++a]);
    } else {
      std::fprintf(stderr, "usage: bench_formfactors [--quick] [--rays R] [--scene PATH]\n");
      return 2;
    }
  }
  Progress::set_enabled(false);
  if (child_target > 0) {
    const FormFactorRun r = run_form_factors(bench::patched_to(scene, std::size_t(child_target), 0.1), rays);
    std::printf("%.6f %.6f %.3f %.0f\n", r.mrays_per_s, r.seconds, r.peak_mb, r.nnz);
    return 0;
  }

  const std::vector<std::size_t> targets = quick ? std::vector<std::size_t>{1000, 10000}
                                                 : std::vector<std::size_t>{1000, 10000, 100000};
  if (quick) rays = std::min(rays, 200L);
  const int all = active_threads();
  std::printf("scene %s, %ld rays per patch, threads 1 and %d\n", scene.c_str(), rays, all);
  std::printf("%8s %7s | %9s %9s %9s | %9s %6s | %8s %9s\n", "patches", "threads", "rtc1", "rtc16", "raw best",
              "ff", "ratio", "nnz/row", "peak MB");
  for (std::size_t t = 0; t < targets.size(); ++t) {
    const PatchSet ps = bench::patched_to(scene, targets[t], 0.1);
    const std::size_t total = ps.size() * std::size_t(rays);
    const RawEmbree raw(ps);
    const std::vector<RTCRay> buffer = make_rays(ps, std::min<std::size_t>(total, std::size_t(1) << 21));
    for (const int threads : {1, all}) {
      ThreadLimit limit(threads);
      // Pick the faster call on the buffer, then time it on as many rays as the form factors shoot.
      const std::size_t probe = std::min(total, buffer.size());
      const double single = raw_throughput(raw, buffer, probe, false);
      const double packet = raw_throughput(raw, buffer, probe, true);
      const double best = raw_throughput(raw, buffer, total, packet > single);
      const bool last = t + 1 == targets.size() && threads == all;
      const FormFactorRun ff = last ? run_in_child(scene, targets[t], rays) : run_form_factors(ps, rays);
      std::printf("%8zu %7d | %9.2f %9.2f %9.2f | %9.2f %6.2f | %8.1f %9.0f%s\n", ps.size(), threads, single, packet,
                  best, ff.mrays_per_s, ff.mrays_per_s / best, ff.nnz / double(ps.size()), ff.peak_mb,
                  last ? " (child process)" : "");
      std::fflush(stdout);
    }
  }
  std::printf("Mrays/s; rtc1/rtc16 on up to 2^21 pregenerated rays, raw best on the same ray count as ff;\n"
              "peak MB is this process's peak so far, except the child-process row (its own peak)\n");
  return 0;
}
