// bench_scale: time and peak memory of every stage against the patch count N, and the ray kernel's and the path
// tracer's rays per CPU second against raw Embree on the same scene, side by side at each N.
//
// Scene: meshes/cornell_box.obj (or --scene PATH, e.g. the city block of bench/make_city.py) split with
// --max-edge h, h = sqrt(total area / N), so that the patch count is about N (one make_patches: the count is
// printed). Stages, each timed (wall and CPU seconds of the whole process) with its peak resident memory (VmHWM,
// reset before the stage through /proc/self/clear_refs, so a stage's peak includes what earlier stages still hold:
// the patches and the BVH):
//   patching      make_patches(mesh, h)
//   bvh           EmbreeVisibility(patches)
//   raw embree    EmbreeVisibility::intersect on packets of 16 pre-generated incoherent rays (a uniform patch,
//                 a uniform point, a cosine direction: bench_scene.h), --raw-rays of them, tracing only; run
//                 before and after the walks and the path tracer, the better rate kept
//   shoot walks   solve_random_walk shoot-collision, ray kernel, --particles particles (F not stored)
//   gather walks  solve_random_walk gather-collision, ray kernel, --walks walks from each of --targets patches
//                 spread over the scene (defaults: every patch, max(2, 4e6 / N) walks each, so about 4 M walks
//                 at every N and the solve's O(N) set-up, the ray kernel's per-patch records, is paid once
//                 over a run of realistic size)
//   path tracer   estimate_patch_averages (mis), --spp samples per patch on every patch
//   form factors  estimate_form_factors, --ff-rays rays per patch (skipped above --ff-max patches)
//   ff patch order  (--stages ff-order) the same form factors traced in patch order instead of Morton order, side
//                 by side: the CPU ratio, and F checked identical
//   diagnostics   diagnose_form_factors of that F (row sums, reciprocity error: formfactor/transpose_slabs.h)
//   gauss-seidel  solve_gauss_seidel on that F to 1e-6 (sweeps printed)
//   write npz     write_npz(F), then read npz: read_npz (mapped) of the same file
//   write csv     write_patch_csv of B (the path tracer's), one RGB field
//   write vtp     write_vtp of B (the path tracer's), one RGB field
// The ratios: rays per CPU second of the shooting walks, the gathering walks and the path tracer over raw
// Embree's, measured in the same run (CPU seconds: meaningful on a shared machine).
// Usage: bench_scale [--sizes 1e4,1e5,1e6] [--scene PATH] [--particles P] [--walks W] [--targets T] [--spp S]
//                    [--ff-rays R] [--ff-max N] [--raw-rays R] [--stages shoot,gather,pathtrace,vtp,csv,ff-order]
//                    [--integrator mis|nee|implicit] [--out DIR]
// (--spp 0: no path tracer; --stages: which of the walks, the path tracer, the vtp and csv writing and the
// form factors' patch-order comparison run (default all but ff-order),
// e.g. one of them under a profiler; --integrator: the path tracer's, mis by default)
#include <sys/resource.h>
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bench_scene.h"
#include "core/parallel.h"
#include "core/timer.h"
#include "formfactor/form_factor_diagnostics.h"
#include "formfactor/form_factors.h"
#include "formfactor/npz.h"
#include "io/cell_field.h"
#include "io/csv_writer.h"
#include "io/vtp_writer.h"
#include "mesh/read_scene.h"
#include "pathtrace/patch_average.h"
#include "patch/patching.h"
#include "solve/gauss_seidel.h"
#include "solve/problem.h"
#include "visibility/embree_visibility.h"
#include "visibility/ray_packet.h"
#include "walk/random_walk_solver.h"

using namespace radwalk;
using radwalk::bench::cpu_seconds;

namespace {

// Peak resident memory since the last reset_peak(), in GB (VmHWM of /proc/self/status).
double peak_gb() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::atof(line.c_str() + 6) / (1024.0 * 1024.0);
  return 0;
}
void reset_peak() { std::ofstream("/proc/self/clear_refs") << "5"; }

struct Stage {
  double wall = 0, cpu = 0, peak = 0;
};

// Runs f() as one stage: times it and records its peak memory.
template <class F>
Stage stage(const char* name, F&& f) {
  reset_peak();
  const Timer t;
  const double c0 = cpu_seconds();
  f();
  Stage s{t.seconds(), cpu_seconds() - c0, peak_gb()};
  std::printf("  %-14s %9.2f s wall %9.2f s cpu %7.2f GB peak\n", name, s.wall, s.cpu, s.peak);
  std::fflush(stdout);
  return s;
}

std::vector<double> parse_sizes(const std::string& s) {
  std::vector<double> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(std::atof(item.c_str()));
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene = bench::default_scene(), out_dir = std::filesystem::temp_directory_path().string();
  std::vector<double> sizes = {1e4, 1e5, 1e6};
  long particles = 1 << 20, walks = 0, targets = 0, spp = 2, ff_rays = 32, raw_rays = 1 << 21;
  double ff_max = 2e6;
  std::string stages = "shoot,gather,pathtrace,vtp,csv", integrator = "mis";
  for (int a = 1; a + 1 < argc; a += 2) {
    const std::string k = argv[a], v = argv[a + 1];
    if (k == "--sizes") sizes = parse_sizes(v);
    else if (k == "--scene") scene = v;
    else if (k == "--particles") particles = std::atol(v.c_str());
    else if (k == "--walks") walks = std::atol(v.c_str());
    else if (k == "--targets") targets = std::atol(v.c_str());
    else if (k == "--spp") spp = std::atol(v.c_str());
    else if (k == "--ff-rays") ff_rays = std::atol(v.c_str());
    else if (k == "--ff-max") ff_max = std::atof(v.c_str());
    else if (k == "--raw-rays") raw_rays = std::atol(v.c_str());
    else if (k == "--out") out_dir = v;
    else if (k == "--stages") stages = v;
    else if (k == "--integrator") integrator = v;
    else {
      std::fprintf(stderr, "bench_scale: unknown option %s\n", k.c_str());
      return 2;
    }
  }
  std::printf("bench_scale: %s, %d threads; particles %ld, gather %ld walks x %ld patches, spp %ld, "
              "form factors %ld rays per patch (up to %.0f patches), raw rays %ld\n",
              scene.c_str(), active_threads(), particles, walks, targets, spp, ff_rays, ff_max, raw_rays);
  if (spp == 1 || spp < 0) {  // the patch averages need two samples for a variance
    std::fprintf(stderr, "bench_scale: --spp must be 0 (no path tracer) or at least 2 (got %ld)\n", spp);
    return 2;
  }
  std::vector<std::string> stage_list;
  {
    std::stringstream in(stages);
    for (std::string item; std::getline(in, item, ',');) stage_list.push_back(item);
  }
  auto runs = [&](const char* name) { return std::find(stage_list.begin(), stage_list.end(), name) != stage_list.end(); };
  const Mesh mesh = load_scene(scene);
  const double area = make_patches(mesh, 0).total_area();
  std::printf("\n%10s %12s %12s %12s %12s %9s %9s %9s\n", "N", "raw Mray/cs", "shoot", "gather", "pathtrace",
              "shoot/raw", "gath/raw", "pt/raw");
  std::vector<std::string> summary;
  for (const double target : sizes) {
    const double h = std::sqrt(area / target);
    PatchSet ps;
    std::printf("\nN about %.0f (max edge %.4g):\n", target, h);
    stage("patching", [&] { ps = make_patches(mesh, h); });
    const std::size_t N = ps.size();
    std::printf("  %zu patches\n", N);
    std::unique_ptr<EmbreeVisibility> vis;
    stage("bvh", [&] { vis = std::make_unique<EmbreeVisibility>(ps); });

    // Raw Embree: the rays made and packed outside the timing; timed before and after the walks and the path
    // tracer, the better rate kept (the load of a shared machine changes over a run).
    const std::vector<RayPacket> packets = [&] {
      const std::vector<Ray> rays = bench::incoherent_rays(ps, std::size_t(raw_rays), 99);
      std::vector<RayPacket> p((rays.size() + kPacketSize - 1) / kPacketSize);
      for (std::size_t k = 0; k < rays.size(); ++k) {
        p[k / kPacketSize].set(k % kPacketSize, rays[k]);
        p[k / kPacketSize].count = k % kPacketSize + 1;
      }
      return p;
    }();
    double raw_rate = 0;
    auto raw_embree = [&] {
      std::vector<int> hit(packets.size() * kPacketSize);
      const Stage s = stage("raw embree", [&] {
        parallel_chunks(packets.size(), 4096 / kPacketSize, [&](std::size_t b, std::size_t e) {
          Hit hits[kPacketSize];
          for (std::size_t p = b; p < e; ++p) {
            vis->intersect(packets[p], hits);
            for (std::size_t q = 0; q < packets[p].count; ++q) hit[p * kPacketSize + q] = hits[q].patch;
          }
        });
      });
      raw_rate = std::max(raw_rate, double(raw_rays) / s.cpu);
    };
    raw_embree();

    const auto n = static_cast<Eigen::Index>(N);
    const RadiosityProblem walk_problem = make_problem(ps, SparseF(n, n));
    double shoot_rate = 0, gather_rate = 0, pt_rate = 0;
    if (runs("shoot")) {
      WalkOptions o;
      o.method = WalkMethod::shoot_collision;
      o.kernel = WalkKernel::ray;
      o.particles = particles;
      Solution sol;
      const Stage s = stage("shoot walks", [&] { sol = solve_random_walk(walk_problem, &ps, vis.get(), o); });
      shoot_rate = double(sol.steps) / s.cpu;
      std::printf("  %ld rays\n", sol.steps);
    }
    if (runs("gather")) {
      WalkOptions o;
      o.method = WalkMethod::gather_collision;
      o.kernel = WalkKernel::ray;
      const std::size_t m = targets > 0 ? std::min<std::size_t>(N, std::size_t(targets)) : N;
      o.walks_per_patch = walks > 0 ? walks : std::max<long>(2, long(4e6 / double(m)));
      if (m < N)
        for (std::size_t k = 0; k < m; ++k) o.patches.push_back(int(k * N / m));
      Solution sol;
      const Stage s = stage("gather walks", [&] { sol = solve_random_walk(walk_problem, &ps, vis.get(), o); });
      gather_rate = double(sol.steps) / s.cpu;
      std::printf("  %ld rays\n", sol.steps);
    }
    Solution pt;
    pt.B = PatchRgb::Zero(static_cast<Eigen::Index>(N), 3);
    if (spp > 0 && runs("pathtrace")) {  // --spp 0: no path tracer
      PatchAverageOptions o;
      o.spp = spp;
      o.integrator.kind = parse_integrator_kind(integrator);
      o.progress = false;
      const Stage s = stage("path tracer", [&] { pt = estimate_patch_averages(ps, *vis, o); });
      pt_rate = pt.info["rays"] / s.cpu;
      std::printf("  %.0f rays\n", pt.info["rays"]);
    }
    raw_embree();
    if (double(N) <= ff_max) {
      FormFactors ff;
      FormFactorOptions o;
      o.rays_per_patch = ff_rays;
      const Stage s = stage("form factors", [&] { ff = estimate_form_factors(ps, *vis, o); });
      std::printf("  %ld non-zeros, %.2f Mrays per cpu-s\n", long(ff.F.nonZeros()),
                  double(ff_rays) * double(N) / s.cpu / 1e6);
      if (runs("ff-order")) {  // the same F traced in patch order, side by side
        FormFactors plain;
        FormFactorOptions p = o;
        p.morton_order = false;
        const Stage t = stage("ff patch order", [&] { plain = estimate_form_factors(ps, *vis, p); });
        const bool same = plain.F.nonZeros() == ff.F.nonZeros() &&
                          std::equal(plain.F.valuePtr(), plain.F.valuePtr() + plain.F.nonZeros(), ff.F.valuePtr()) &&
                          std::equal(plain.F.innerIndexPtr(), plain.F.innerIndexPtr() + plain.F.nonZeros(),
                                     ff.F.innerIndexPtr());
        std::printf("  patch order / Morton order CPU: %.3f (F %s)\n", t.cpu / s.cpu, same ? "identical" : "DIFFERS");
      }
      stage("diagnostics", [&] { (void)diagnose_form_factors(ff.F, ps.area, ff.rays, ff.back_hits); });
      RadiosityProblem problem = make_problem(ps, std::move(ff.F));
      ff = FormFactors();
      {
        SolveOptions so;
        so.tol = 1e-6;
        Solution gs;
        stage("gauss-seidel", [&] { gs = solve_gauss_seidel(problem, so); });
        std::printf("  %ld sweeps\n", gs.iterations);
      }
      const std::string path = out_dir + "/bench_scale_F.npz";
      stage("write npz", [&] { write_npz(path, problem.F); });
      std::printf("  %.2f GB file\n", double(std::filesystem::file_size(path)) / 1e9);
      SparseF back;
      stage("read npz", [&] { back = read_npz(path, N); });
      std::filesystem::remove(path);
    }
    if (runs("csv")) {
      const std::string path = out_dir + "/bench_scale_B.csv";
      stage("write csv", [&] { write_patch_csv(path, ps, {rgb_field("B", pt.B)}); });
      std::filesystem::remove(path);
    }
    if (runs("vtp")) {
      const std::string path = out_dir + "/bench_scale_B.vtp";
      stage("write vtp", [&] { write_vtp(path, ps, {rgb_field("B", pt.B)}); });
      std::filesystem::remove(path);
    }
    char line[256];
    std::snprintf(line, sizeof line, "%10zu %12.2f %12.2f %12.2f %12.2f %9.2f %9.2f %9.2f", N, raw_rate / 1e6,
                  shoot_rate / 1e6, gather_rate / 1e6, pt_rate / 1e6, shoot_rate / raw_rate, gather_rate / raw_rate,
                  pt_rate / raw_rate);
    summary.push_back(line);
    std::printf("%s\n", line);
  }
  std::printf("\nrays per CPU second (millions) and ratios to raw Embree (target >= 0.6):\n%10s %12s %12s %12s %12s "
              "%9s %9s %9s\n",
              "N", "raw", "shoot", "gather", "pathtrace", "shoot/raw", "gath/raw", "pt/raw");
  for (const std::string& s : summary) std::printf("%s\n", s.c_str());
  return 0;
}
