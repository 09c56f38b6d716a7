// bench_error_vs_rays: error against rays traced and against CPU and wall seconds, for every ray-kernel
// random-walk method and sampler, on the bundled Cornell box. Not a test.
//
// Error measure (docs/measurements.md, "Which method when"): with x the reference and y the estimate per patch, channel means
// xbar_i, ybar_i,
//   e = sqrt( sum_i A_i (ybar_i - xbar_i)^2 / sum_i A_i xbar_i^2 ),
// over the patches that are not emitters and not fully enclosed (all of 64 rays from the patch hit a back face).
// Reference: the mean of two independent long runs (seeds 1001, 1002) of --sampler sobol --direct-light
// shoot-collision; their own error is estimated as e(ref1, ref2) / 2 (the mean of two independent estimates has
// half the variance of their difference) and printed, so one sees that it is at least ten times below the
// levels measured. A second, independent check: a long run of the random sampler (pseudo-random shoot-collision,
// another estimator path) against the reference, with the error its own standard errors predict,
//   e_pred = sqrt( sum_i A_i mean_c(se_ic)^2 / sum_i A_i xbar_i^2 ),
// a bias in either method shows as e > e_pred.
// Per method and budget (rays), R runs (seeds 1 .. R; --repeat, default 3): e, rays traced (Solution::steps:
// every ray, shadow rays included), CPU seconds of the process and wall seconds of the call; the medians are
// printed and every run goes to the CSV. The method's count (particles or walks per patch) for a ray budget
// comes from a pilot run's rays per particle (walk). Raw Embree's rays per CPU second (EmbreeVisibility on
// packets of 16 pre-made incoherent rays, bench_walks.cpp's measure, all threads) is measured in the same run, so
// speed is given as the ratio (method rays per CPU second) / (raw rays per CPU second).
// Then, per method, the rays needed for e = 0.8 % and 0.3 % (log-log interpolation between the measured
// budgets; ">" when beyond the largest).
// Usage: bench_error_vs_rays [--quick] [--repeat R] [--max-edge H[,H...]] [--csv PATH] [--ref-particles N]
//                            [--scene PATH] [--methods A,B,...] [--threads T] [--budgets B1,B2,...]   (default meshes/cornell_box.obj of the current directory, run from
//                            the source tree, else the one next to the bench sources)
//   default --max-edge 100,50 (328 and 975 patches on today's patching), --csv bench_error_vs_rays.csv.
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <optional>
#include <vector>

#include "bench_scene.h"
#include "core/parallel.h"
#include "core/timer.h"
#include "formfactor/emitter_form_factors.h"
#include "mesh/read_scene.h"
#include "patch/patching.h"
#include "solve/direct_solver.h"
#include "solve/problem.h"
#include "visibility/embree_visibility.h"
#include "visibility/ray_packet.h"
#include "walk/random_walk_solver.h"
#include "walk/ray_kernel.h"

using namespace radwalk;
using radwalk::bench::cpu_seconds;

namespace {

// The form-factor route with emitter columns: the share of each patch's rays that are shadow samples of the
// emitter columns (the rest are cosine rays).
double g_shadow_fraction = 0.25;  // --shadow-fraction

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// One method of the table: a random-walk method with its walk options (count filled per budget), or the
// form-factor route (F from R rays per patch, then the direct solve), with a fraction of R spent on the emitter
// columns (formfactor/emitter_form_factors.h; 0: cosine rays only).
struct Method {
  std::string name;
  WalkOptions options;
  bool form_factor_route = false;
  double shadow_fraction = 0;
  bool sobol = false;  // FormFactorOptions::sobol for the cosine rays
};

std::vector<Method> methods() {
  std::vector<Method> m;
  auto add = [&](const std::string& name, const std::string& walk, WalkSampler sampler, bool direct,
                 bool sampled = false) {
    Method x{name, {}};
    x.options.method = parse_walk_method(walk);
    x.options.kernel = WalkKernel::ray;
    x.options.sampler = sampler;
    x.options.direct_light = direct;
    x.options.direct_sampled = sampled;
    m.push_back(x);
  };
  add("gather-collision", "gather-collision", WalkSampler::random, false);
  add("gather-expected-value", "gather-expected-value", WalkSampler::random, false);
  add("shoot-absorption", "shoot-absorption", WalkSampler::random, false);
  add("shoot-collision", "shoot-collision", WalkSampler::random, false);
  add("shoot-collision sobol", "shoot-collision", WalkSampler::sobol, false);
  add("shoot-collision sobol+direct", "shoot-collision", WalkSampler::sobol, true, true);
  add("shoot-collision sobol+visible", "shoot-collision", WalkSampler::sobol, true, false);
  add("stochastic-jacobi", "shoot-collision", WalkSampler::jacobi, false);
  add("stochastic-jacobi+visible", "shoot-collision", WalkSampler::jacobi, true, false);
  Method ff{"formfactors+direct-solve", {}, true, 0.0};
  m.push_back(ff);
  ff.name = "formfactors emitter-cols+direct-solve";
  ff.shadow_fraction = g_shadow_fraction;
  m.push_back(ff);
  ff.name = "formfactors sobol+emitter-cols+direct-solve";
  ff.sobol = true;
  m.push_back(ff);

  return m;
}

// Sets the method's count so that it traces about `rays` rays, given `per_unit` rays per particle (shooting)
// or per walk (gathering).
void set_budget(WalkOptions& o, double rays, double per_unit, std::size_t N) {
  if (is_gathering(o.method))
    o.walks_per_patch = std::max(2L, long(rays / (per_unit * double(N))));
  else
    o.particles = std::max(long(2 * o.replicates), long(rays / per_unit));
}

// The patches the error is measured over: not emitters, not fully enclosed (all of 64 cosine rays back hits).
std::vector<char> measured_patches(const RadiosityProblem& problem, const PatchSet& patches,
                                   const Visibility& vis) {
  const std::size_t N = patches.size();
  const RayKernel kernel(problem, patches, vis, std::vector<double>(N, 0.5));
  std::vector<char> mask(N, 0);
  for (std::size_t k = 0; k < N; ++k) {
    if (problem.E.row(Eigen::Index(k)).maxCoeff() > 0) continue;
    Rng rng = stream(5, StreamDomain::benchmark, k);
    WalkCounters c;
    for (int s = 0; s < 64; ++s) kernel.sample(k, rng, c);
    mask[k] = c.back_hits < 64;
  }
  return mask;
}

// e of y against x over the mask (the top of this file).
double error_of(const PatchRgb& y, const PatchRgb& x, const Eigen::VectorXd& area, const std::vector<char>& mask) {
  double num = 0, den = 0;
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    if (!mask[std::size_t(i)]) continue;
    const double xb = x.row(i).mean(), yb = y.row(i).mean();
    num += area(i) * (yb - xb) * (yb - xb);
    den += area(i) * xb * xb;
  }
  return std::sqrt(num / den);
}

// The error a solution's own standard errors predict against x.
double predicted_error(const Solution& s, const PatchRgb& x, const Eigen::VectorXd& area,
                       const std::vector<char>& mask) {
  double num = 0, den = 0;
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    if (!mask[std::size_t(i)]) continue;
    const double se = s.B_se.row(i).mean(), xb = x.row(i).mean();
    num += area(i) * se * se;
    den += area(i) * xb * xb;
  }
  return std::sqrt(num / den);
}

// Raw Embree rays per CPU second (packets of 16, all threads).
double raw_embree_rate(const EmbreeVisibility& vis, const PatchSet& patches, std::size_t n, int repeat) {
  const std::vector<Ray> rays = bench::incoherent_rays(patches, n, 99);
  std::vector<RayPacket> packets((n + kPacketSize - 1) / kPacketSize);
  for (std::size_t k = 0; k < n; ++k) {
    packets[k / kPacketSize].set(k % kPacketSize, rays[k]);
    packets[k / kPacketSize].count = k % kPacketSize + 1;
  }
  std::vector<int> hit(n);
  double best = 0;
  for (int r = 0; r < repeat; ++r) {
    const double c0 = cpu_seconds();
    parallel_chunks(packets.size(), 4096 / kPacketSize, [&](std::size_t b, std::size_t e) {
      Hit hits[kPacketSize];
      for (std::size_t p = b; p < e; ++p) {
        vis.intersect(packets[p], hits);
        for (std::size_t q = 0; q < packets[p].count; ++q) hit[p * kPacketSize + q] = hits[q].patch;
      }
    });
    best = std::max(best, double(n) / (cpu_seconds() - c0));
  }
  return best;
}

struct Run {
  double e, rays, cpu, wall;
};

Run run_once(const RadiosityProblem& problem, const PatchSet& patches, const Visibility& vis, const WalkOptions& o,
             const PatchRgb& ref, const std::vector<char>& mask) {
  const Timer wall;
  const double c0 = cpu_seconds();
  const Solution s = solve_random_walk(problem, &patches, &vis, o);
  const double c = cpu_seconds() - c0, w = wall.seconds();
  return {error_of(s.B, ref, problem.area, mask), double(s.steps), c, w};
}

// The form-factor route at `rays` rays in all: R = rays / N per patch, a share f of them shadow samples of the
// emitter columns, then the direct solve. Rays counted: the cosine rays and the shadow rays traced.
Run run_form_factor_route(const PatchSet& patches, const Visibility& vis, double rays, double f, bool sobol,
                          std::uint64_t seed, const PatchRgb& ref, const std::vector<char>& mask) {
  const Timer wall;
  const double c0 = cpu_seconds();
  const double N = double(patches.size());
  const double R = rays / N;
  FormFactorOptions fo;
  fo.seed = seed;
  fo.sobol = sobol;
  fo.rays_per_patch = std::max(16L, long(R * (1 - f)));
  double traced = N * double(fo.rays_per_patch);
  SparseF F;
  if (f > 0) {
    EmitterFormFactors ef = estimate_emitter_form_factors(patches, vis, fo, std::max(1L, long(R * f)));
    traced += double(ef.shadow_rays);
    F = std::move(ef.form_factors.F);
  } else {
    F = estimate_form_factors(patches, vis, fo).F;
  }
  const RadiosityProblem p = make_problem(patches, std::move(F));
  const Solution s = solve_direct(p);
  const double c = cpu_seconds() - c0, w = wall.seconds();
  return {s.B.rows() ? error_of(s.B, ref, p.area, mask) : 1.0, traced, c, w};
}

// --methods A,B,...: the methods whose name contains one of the comma-separated parts (empty: all).
bool selected(const std::string& name, const std::string& only) {
  if (only.empty()) return true;
  std::stringstream ss(only);
  for (std::string part; std::getline(ss, part, ',');)
    if (!part.empty() && name.find(part) != std::string::npos) return true;
  return false;
}

// Rays for the error target by log-log interpolation of the median curve (budgets ascending).
std::string rays_for(const std::vector<double>& rays, const std::vector<double>& err, double target) {
  char buf[64];
  for (std::size_t k = 0; k < rays.size(); ++k) {
    if (err[k] > target) continue;
    if (k == 0) {
      std::snprintf(buf, sizeof buf, "<= %.3g", rays[0]);
      return buf;
    }
    const double t = std::log(err[k - 1] / target) / std::log(err[k - 1] / err[k]);
    std::snprintf(buf, sizeof buf, "%.3g", std::exp(std::log(rays[k - 1]) + t * std::log(rays[k] / rays[k - 1])));
    return buf;
  }
  std::snprintf(buf, sizeof buf, "> %.3g", rays.back());
  return buf;
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  int repeat = 3;
  std::vector<double> max_edges = {100, 50};
  std::string csv_path = "bench_error_vs_rays.csv";
  long ref_particles = 0;
  std::string only;  // --methods A,B,...: only the methods whose name contains one of the parts
  int threads = 0;   // --threads T: at most T threads (0: all)
  std::vector<double> budget_list;  // --budgets B1,B2,...: the ray budgets (default below)
  std::string scene = std::filesystem::exists("meshes/cornell_box.obj") ? "meshes/cornell_box.obj"
                                                                         : bench::default_scene();
  for (int a = 1; a < argc; ++a) {
    if (!std::strcmp(argv[a], "--quick")) quick = true;
    else if (!std::strcmp(argv[a], "--repeat") && a + 1 < argc) repeat = std::max(1, std::atoi(argv[++a]));
    else if (!std::strcmp(argv[a], "--csv") && a + 1 < argc) csv_path = argv[++a];
    else if (!std::strcmp(argv[a], "--scene") && a + 1 < argc) scene = argv[++a];
    else if (!std::strcmp(argv[a], "--methods") && a + 1 < argc) only = argv[++a];
    else if (!std::strcmp(argv[a], "--ref-particles") && a + 1 < argc) ref_particles = std::atol(argv[++a]);
    else if (!std::strcmp(argv[a], "--shadow-fraction") && a + 1 < argc) g_shadow_fraction = std::atof(argv[++a]);
    else if (!std::strcmp(argv[a], "--threads") && a + 1 < argc) threads = std::max(1, std::atoi(argv[++a]));
    else if (!std::strcmp(argv[a], "--budgets") && a + 1 < argc) {
      budget_list.clear();
      std::stringstream ss(argv[++a]);
      for (std::string b; std::getline(ss, b, ',');) budget_list.push_back(std::atof(b.c_str()));
    }
    else if (!std::strcmp(argv[a], "--max-edge") && a + 1 < argc) {
      max_edges.clear();
      std::stringstream ss(argv[++a]);
      for (std::string h; std::getline(ss, h, ',');) max_edges.push_back(std::atof(h.c_str()));
    }
    else {
      std::fprintf(stderr,
                   "bench_error_vs_rays: unknown option or missing value '%s'; options: --quick, --repeat N, --csv FILE, "
                   "--scene OBJ, --methods A,B, --ref-particles N, --shadow-fraction F, --threads T, --budgets B1,B2, "
                   "--max-edge H1,H2\n",
                   argv[a]);
      return 2;
    }
  }
  std::vector<double> budgets =
      quick ? std::vector<double>{1e5, 4e5, 1.6e6} : std::vector<double>{1e5, 4e5, 1.6e6, 6.4e6};
  if (!budget_list.empty()) budgets = budget_list;
  std::optional<ThreadLimit> limit;
  if (threads > 0) limit.emplace(threads);
  if (ref_particles == 0) ref_particles = quick ? 8'000'000 : 40'000'000;
  std::ofstream csv(csv_path);
  csv << "patches,method,budget,seed,rays,cpu_seconds,wall_seconds,error,raw_embree_rays_per_cpu_second\n";
  const Mesh mesh = load_scene(scene);
  for (const double h : max_edges) {
    const PatchSet patches = make_patches(mesh, h);
    const std::size_t N = patches.size();
    const EmbreeVisibility vis(patches);
    const RadiosityProblem problem = make_problem(patches, SparseF(Eigen::Index(N), Eigen::Index(N)));
    const std::vector<char> mask = measured_patches(problem, patches, vis);
    std::size_t measured = 0;
    for (char m : mask) measured += m;
    std::printf("Cornell box, --max-edge %g: %zu patches (%zu measured: not emitters, not enclosed), %d threads\n",
                h, N, measured, active_threads());
    // Reference: two independent long runs of the best method.
    WalkOptions ro;
    ro.method = WalkMethod::shoot_collision;
    ro.kernel = WalkKernel::ray;
    ro.sampler = WalkSampler::sobol;
    ro.direct_light = true;
    ro.particles = ref_particles;
    ro.seed = 1001;
    const Solution ref1 = solve_random_walk(problem, &patches, &vis, ro);
    ro.seed = 1002;
    const Solution ref2 = solve_random_walk(problem, &patches, &vis, ro);
    const PatchRgb ref = 0.5 * (ref1.B + ref2.B);
    const double ref_error = 0.5 * error_of(ref1.B, ref2.B, problem.area, mask);
    std::printf("reference: mean of 2 runs of sobol+direct shoot-collision, %ld particles and %.3g rays each; "
                "its own error e(ref1, ref2) / 2 = %.4f %%\n",
                ref_particles, double(ref1.steps), 100 * ref_error);
    {
      WalkOptions co;
      co.method = WalkMethod::shoot_collision;
      co.kernel = WalkKernel::ray;
      co.particles = quick ? 2'000'000 : 10'000'000;
      co.seed = 2001;
      const Solution check = solve_random_walk(problem, &patches, &vis, co);
      std::printf("independent check: random shoot-collision, %ld particles: e = %.4f %% against the reference, "
                  "its standard errors predict %.4f %% (with the reference's: %.4f %%)\n",
                  co.particles, 100 * error_of(check.B, ref, problem.area, mask),
                  100 * predicted_error(check, ref, problem.area, mask),
                  100 * std::hypot(predicted_error(check, ref, problem.area, mask), ref_error));
    }
    const double raw = raw_embree_rate(vis, patches, quick ? 1'000'000 : 4'000'000, 3);
    std::printf("raw Embree (packets of 16, %d threads): %.2f M rays per CPU second\n\n", active_threads(),
                raw / 1e6);
    std::printf("%-30s %10s %10s %9s %9s %9s %12s\n", "method", "budget", "rays", "cpu s", "wall s", "e %",
                "speed/raw");
    struct Curve {
      std::string name;
      std::vector<double> rays, err;
    };
    std::vector<Curve> curves;
    for (Method m : methods()) {
      if (!selected(m.name, only)) continue;
      // Pilot: rays per particle (walk).
      double per_unit = 1;
      if (!m.form_factor_route) {
        WalkOptions pilot = m.options;
        set_budget(pilot, 2e5, 1.0, N);
        pilot.seed = 999;
        const Solution ps = solve_random_walk(problem, &patches, &vis, pilot);
        per_unit = double(ps.steps) / double(total_walks(pilot, N));
      }
      Curve curve{m.name, {}, {}};
      for (const double budget : budgets) {
        if (!m.form_factor_route && is_gathering(m.options.method) && budget > 1.7e6) continue;  // far behind: skip the long runs
        WalkOptions o = m.options;
        set_budget(o, budget, per_unit, N);
        std::vector<double> e, rays, cpu, wall;
        for (int r = 0; r < repeat; ++r) {
          o.seed = std::uint64_t(r + 1);
          const Run run = m.form_factor_route
                              ? run_form_factor_route(patches, vis, budget, m.shadow_fraction, m.sobol, o.seed, ref, mask)
                              : run_once(problem, patches, vis, o, ref, mask);
          e.push_back(run.e);
          rays.push_back(run.rays);
          cpu.push_back(run.cpu);
          wall.push_back(run.wall);
          csv << N << ',' << m.name << ',' << budget << ',' << o.seed << ',' << run.rays << ',' << run.cpu << ','
              << run.wall << ',' << run.e << ',' << raw << '\n';
        }
        const double mr = median(rays), mc = median(cpu);
        std::printf("%-30s %10.3g %10.3g %9.3f %9.3f %9.3f %12.2f\n", m.name.c_str(), budget, mr, mc,
                    median(wall), 100 * median(e), (mr / mc) / raw);
        std::fflush(stdout);
        curve.rays.push_back(mr);
        curve.err.push_back(median(e));
      }
      curves.push_back(curve);
    }
    std::printf("\n%-30s %16s %16s   (targets at 328 patches: <= 4e5 and <= 2.5e6 rays)\n", "rays needed for",
                "e = 0.8 %", "e = 0.3 %");
    for (const Curve& c : curves)
      std::printf("%-30s %16s %16s\n", c.name.c_str(), rays_for(c.rays, c.err, 0.008).c_str(),
                  rays_for(c.rays, c.err, 0.003).c_str());
    std::printf("\n");
  }
  std::printf("wrote %s\n", csv_path.c_str());
  return 0;
}
