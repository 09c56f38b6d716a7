// bench_analytic_city: the analytic form-factor route (formfactor/analytic_form_factors.h) on city blocks written by
// bench/make_city.py. Not a test. Two parts:
//
//   compare CITY.obj --max-edge H   the analytic route (no cut-off; one thread) against the ray route at equal CPU:
//       stratified, Sobol, and Sobol with emitter columns (a third of the samples as shadow samples of the emitter
//       columns), each with its rays per patch set from a calibration run so that its CPU seconds match the
//       analytic route's; then each again at 4x those rays. Reference: the ray route with Sobol rays and emitter
//       columns at --ref-rays rays and --ref-rays / 4 shadow samples per patch (all threads), twice with two
//       seeds: e_B between the two references / sqrt(2) is printed as the reference's own e_B noise, under which no
//       difference can be resolved. Columns as bench_analytic: per-pair RMS error against the reference, the
//       largest row-sum error, e_B = sqrt(sum_i A_i |B_i - B_ref_i|^2 / sum_i A_i |B_ref_i|^2) over the three
//       channels (the scene's own emitters and reflectances), CPU seconds of the form factors.
//   scaling [--cutoff TAU] CITY.obj H [CITY.obj H ...]   time of the analytic route against N: for each scene, N,
//       the pairs kept, dropped and sampled, the shadow rays, the CPU seconds of the pair enumeration alone and of
//       the whole route (all threads: CPU seconds add up), the largest per-row bound of the dropped sum and its
//       area-weighted estimate; then the exponent b of time ~ N^b between successive scenes and by least squares.
//       --cutoff-rays N: the dropped pairs completed by N cosine rays a patch (the row then also prints the
//       completed pairs and the mean row sum, area-weighted). --enumerate-only: the tree and its traversal alone (the exponent is then that of the enumeration's time),
//       with the candidate pairs it leaves to compute against the N (N - 1) / 2 of brute force.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "bench_scene.h"
#include "core/parallel.h"
#include "formfactor/analytic_form_factors.h"
#include "formfactor/emitter_form_factors.h"
#include "formfactor/form_factors.h"
#include "formfactor/patch_pair_tree.h"
#include "mesh/read_scene.h"
#include "patch/patching.h"
#include "solve/direct_solver.h"
#include "solve/problem.h"
#include "visibility/embree_visibility.h"

using namespace radwalk;
using radwalk::bench::cpu_seconds;

namespace {

PatchRgb solve_B(const PatchSet& ps, const SparseF& F) { return solve_direct(make_problem(ps, F)).B; }

double e_B(const PatchSet& ps, const PatchRgb& B, const PatchRgb& ref) {
  double num = 0, den = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    num += ps.area[i] * (B.row(Eigen::Index(i)) - ref.row(Eigen::Index(i))).square().sum();
    den += ps.area[i] * ref.row(Eigen::Index(i)).square().sum();
  }
  return std::sqrt(num / den);
}

std::vector<double> dense_of(const SparseF& F) {
  const std::size_t N = std::size_t(F.rows());
  std::vector<double> d(N * N, 0.0);
  for (std::size_t i = 0; i < N; ++i)
    for (SparseF::InnerIterator it(F, Eigen::Index(i)); it; ++it) d[i * N + std::size_t(it.col())] = it.value();
  return d;
}

void compare_rows(const SparseF& F, const std::vector<double>& ref, std::size_t N, double& rms, double& row_error) {
  double sum2 = 0;
  std::size_t count = 0;
  row_error = 0;
  std::vector<double> dense(N);
  for (std::size_t i = 0; i < N; ++i) {
    std::fill(dense.begin(), dense.end(), 0.0);
    double row = 0, row_ref = 0;
    for (SparseF::InnerIterator it(F, Eigen::Index(i)); it; ++it) dense[std::size_t(it.col())] = it.value(), row += it.value();
    for (std::size_t j = 0; j < N; ++j) {
      const double r = ref[i * N + j];
      row_ref += r;
      if (r == 0 && dense[j] == 0) continue;
      sum2 += (dense[j] - r) * (dense[j] - r);
      ++count;
    }
    row_error = std::max(row_error, std::abs(row - row_ref));
  }
  rms = std::sqrt(sum2 / double(std::max<std::size_t>(count, 1)));
}

SparseF ray_route(const PatchSet& ps, const Visibility& vis, long rays, bool sobol, long emitter_samples,
                  std::uint64_t seed) {
  FormFactorOptions o;
  o.rays_per_patch = rays;
  o.sobol = sobol;
  o.seed = seed;
  if (emitter_samples > 0) return estimate_emitter_form_factors(ps, vis, o, emitter_samples).form_factors.F;
  return estimate_form_factors(ps, vis, o).F;
}

int compare(const std::string& path, double h, long ref_rays) {
  const PatchSet ps = make_patches(load_scene(path), h);
  const std::size_t N = ps.size();
  const EmbreeVisibility vis(ps);
  std::printf("bench_analytic_city compare: %s at --max-edge %g: %zu patches\n", path.c_str(), h, N);
  // The reference, twice.
  std::vector<double> ref;
  PatchRgb Bref, Bref2;
  {
    ThreadLimit all(0);
    const SparseF F1 = ray_route(ps, vis, ref_rays, true, ref_rays / 4, 1234);
    const SparseF F2 = ray_route(ps, vis, ref_rays, true, ref_rays / 4, 4321);
    ref = dense_of(F1);
    Bref = solve_B(ps, F1);
    Bref2 = solve_B(ps, F2);
  }
  const double ref_noise = e_B(ps, Bref2, Bref) / std::sqrt(2.0);
  std::printf("reference: Sobol rays + emitter columns, %ld rays and %ld shadow samples per patch; its own e_B noise "
              "%.2e (two seeds' e_B / sqrt 2)\n",
              ref_rays, ref_rays / 4, ref_noise);
  ThreadLimit one(1);
  struct Row {
    std::string method;
    long rays = 0;
    double rms = 0, row_error = 0, eB = 0, cpu = 0;
  };
  std::vector<Row> rows;
  const auto measure = [&](const std::string& method, long rays, auto&& make) {
    const double t0 = cpu_seconds();
    const SparseF F = make();
    Row r;
    r.method = method;
    r.rays = rays;
    r.cpu = cpu_seconds() - t0;
    compare_rows(F, ref, N, r.rms, r.row_error);
    r.eB = e_B(ps, solve_B(ps, F), Bref);
    rows.push_back(r);
    std::fprintf(stderr, "  %s done (%.2f s)\n", method.c_str(), r.cpu);
    return r.cpu;
  };
  const double t_analytic = measure("analytic", 0, [&] { return analytic_form_factors(ps, vis).form_factors.F; });
  struct Variant {
    const char* name;
    bool sobol;
    bool emitter;
  };
  for (const Variant v : {Variant{"stratified", false, false}, Variant{"sobol", true, false},
                          Variant{"sobol + emitter columns", true, true}}) {
    // Calibration: CPU per ray at 1000 rays (and 333 shadow samples) per patch.
    const double t0 = cpu_seconds();
    ray_route(ps, vis, 1000, v.sobol, v.emitter ? 333 : 0, 99);
    const double per = (cpu_seconds() - t0) / 1000.0;
    for (int scale : {1, 4}) {
      const long rays = std::max(16L, long(std::lround(scale * t_analytic / per)));
      measure(std::string(v.name) + (scale == 1 ? " (equal CPU)" : " (4x CPU)"), rays,
              [&] { return ray_route(ps, vis, rays, v.sobol, v.emitter ? rays / 3 : 0, 7); });
    }
  }
  std::printf("%-36s %10s %14s %14s %12s %10s\n", "method", "rays/patch", "per-pair RMS", "row-sum error", "e_B", "CPU s");
  for (const Row& r : rows)
    std::printf("%-36s %10ld %14.3e %14.3e %12.3e %10.3f\n", r.method.c_str(), r.rays, r.rms, r.row_error, r.eB, r.cpu);
  std::printf("(rays/patch of 'sobol + emitter columns': the cosine rays; a third as many shadow samples besides)\n");
  return 0;
}

int scaling(const std::vector<std::pair<std::string, double>>& scenes, double cutoff, bool enumerate_only,
            long cutoff_rays) {
  std::printf("bench_analytic_city scaling: cut-off %g; CPU seconds of the process (all threads)\n", cutoff);
  std::printf("%9s %12s %14s %12s %12s %10s %10s %12s %12s\n", "N", "pairs kept", "pairs dropped", "sampled",
              "rays", "enum CPU s", "CPU s", "max bound", "est. (area)");
  std::vector<double> logN, logT;
  for (const auto& [path, h] : scenes) {
    const PatchSet ps = make_patches(load_scene(path), h);
    const EmbreeVisibility vis(ps);
    double t0 = cpu_seconds();
    const PatchPairTree tree(ps);
    const PatchPairEnumeration e = tree.enumerate(cutoff);
    const double t_enum = cpu_seconds() - t0;
    if (enumerate_only) {  // the tree and its traversal only: the pairs it leaves to compute, and the dropped ones
      std::uint64_t candidates = 0;
      for (const auto& lp : e.leaf_pairs) {
        const std::uint64_t na = std::uint64_t(tree.leaf_count(lp[0])), nb = std::uint64_t(tree.leaf_count(lp[1]));
        candidates += lp[0] == lp[1] ? na * (na - 1) / 2 : na * nb;
      }
      double bound = 0, est = 0;
      for (std::size_t i = 0; i < ps.size(); ++i) {
        bound = std::max(bound, e.cutoff_bound[i]);
        est += ps.area[i] * e.cutoff_estimate[i];
      }
      est /= ps.total_area();
      std::printf("%9zu %12llu %14llu %12s %12s %10.2f %10s %12.3e %12.3e  (candidate pairs, of %.3g)\n", ps.size(),
                  (unsigned long long)candidates, (unsigned long long)e.dropped_pairs, "-", "-", t_enum, "-", bound,
                  est, 0.5 * double(ps.size()) * double(ps.size() - 1));
      std::fflush(stdout);
      logN.push_back(std::log(double(ps.size())));
      logT.push_back(std::log(std::max(t_enum, 1e-3)));
      continue;
    }
    AnalyticFormFactorOptions o;
    o.cutoff = cutoff;
    o.cutoff_rays = cutoff_rays;
    o.max_patches = std::size_t(1) << 40;
    t0 = cpu_seconds();
    const AnalyticFormFactors a = analytic_form_factors(ps, vis, o);
    const double t = cpu_seconds() - t0;
    double bound = 0, est = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      bound = std::max(bound, a.cutoff_bound[i]);
      est += ps.area[i] * a.cutoff_estimate[i];
    }
    est /= ps.total_area();
    if (cutoff_rays > 0) {
      double rows = 0;
      for (std::size_t i = 0; i < ps.size(); ++i) {
        double r = 0;
        for (SparseF::InnerIterator it(a.form_factors.F, Eigen::Index(i)); it; ++it) r += it.value();
        rows += ps.area[i] * r;
      }
      std::printf("  completion: %llu pairs estimated by %llu cosine rays; area-weighted mean row sum %.4f\n",
                  (unsigned long long)a.completed_pairs, (unsigned long long)a.cutoff_rays, rows / ps.total_area());
    }
    std::printf("%9zu %12llu %14llu %12llu %12llu %10.2f %10.2f %12.3e %12.3e\n", ps.size(),
                (unsigned long long)(a.form_factors.F.nonZeros() / 2), (unsigned long long)a.dropped_pairs,
                (unsigned long long)a.sampled_pairs, (unsigned long long)a.visibility_rays, t_enum, t, bound, est);
    std::fflush(stdout);
    logN.push_back(std::log(double(ps.size())));
    logT.push_back(std::log(t));
  }
  for (std::size_t k = 1; k < logN.size(); ++k)
    std::printf("exponent between N = %.0f and %.0f: %.2f\n", std::exp(logN[k - 1]), std::exp(logN[k]),
                (logT[k] - logT[k - 1]) / (logN[k] - logN[k - 1]));
  if (logN.size() >= 2) {
    double mx = 0, my = 0;
    for (std::size_t k = 0; k < logN.size(); ++k) mx += logN[k], my += logT[k];
    mx /= double(logN.size());
    my /= double(logN.size());
    double sxy = 0, sxx = 0;
    for (std::size_t k = 0; k < logN.size(); ++k) sxy += (logN[k] - mx) * (logT[k] - my), sxx += (logN[k] - mx) * (logN[k] - mx);
    std::printf("least-squares exponent of CPU seconds ~ N^b: b = %.2f\n", sxy / sxx);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const auto usage = [] {
    std::fprintf(stderr,
                 "usage: bench_analytic_city compare CITY.obj --max-edge H [--ref-rays R]\n"
                 "       bench_analytic_city scaling [--cutoff TAU] [--enumerate-only] [--cutoff-rays N] CITY.obj H [CITY.obj H ...]\n");
    return 2;
  };
  if (argc < 2) return usage();
  const std::string mode = argv[1];
  if (mode == "compare") {
    std::string path;
    double h = 10;
    long ref_rays = 1L << 16;
    for (int a = 2; a < argc; ++a) {
      const std::string arg = argv[a];
      if (arg == "--max-edge" && a + 1 < argc) h = std::stod(argv[++a]);
      else if (arg == "--ref-rays" && a + 1 < argc) ref_rays = std::stol(argv[++a]);
      else if (path.empty() && arg[0] != '-') path = arg;
      else return usage();
    }
    if (path.empty()) return usage();
    return compare(path, h, ref_rays);
  }
  if (mode == "scaling") {
    double cutoff = 1e-3;
    bool enumerate_only = false;
    long cutoff_rays = 0;
    std::vector<std::pair<std::string, double>> scenes;
    for (int a = 2; a < argc; ++a) {
      const std::string arg = argv[a];
      if (arg == "--cutoff" && a + 1 < argc) cutoff = std::stod(argv[++a]);
      else if (arg == "--enumerate-only") enumerate_only = true;
      else if (arg == "--cutoff-rays" && a + 1 < argc) cutoff_rays = std::stol(argv[++a]);
      else if (a + 1 < argc) scenes.push_back({arg, std::stod(argv[a + 1])}), ++a;
      else return usage();
    }
    if (scenes.empty()) return usage();
    return scaling(scenes, cutoff, enumerate_only, cutoff_rays);
  }
  return usage();
}
