// bench_analytic: the analytic form-factor route (formfactor/analytic_form_factors.h) against Monte Carlo form
// factors at 1e3 and 1e4 rays per patch (stratified pseudo-random and randomised Sobol), side by side, one thread
// each (CPU seconds of the process while the form factors are computed). Not a test.
//
// Scenes:
//   cube      the unit cube, k x k patches a wall (k = 13: 1,014 patches), nothing occluded; the ceiling emits
//             E = 1, every wall has rho = 0.5. Reference F: every pair from the closed forms C-11 and C-14 by
//             superposition (tests/support/view_factors.h, axis_rectangle_exchange_area), in double; independent
//             of the contour integral. Reference B: the direct solve with the reference F.
//   cornell   meshes/cornell_box.obj patched to about 1,000 patches (bench_scene.h; the blocks stand on the floor).
//             Reference F: Monte Carlo with Sobol rays, --ref-rays per patch (default 2^17); its own per-pair RMS
//             noise, sqrt(mean F (1 - F) / n) over the compared pairs, is printed beside, as the floor under which
//             no difference can be resolved. Reference B: the direct solve with it.
// Columns: per-pair RMS error sqrt(mean over ordered pairs with F_ij or F_ref_ij non-zero of (F_ij - F_ref_ij)^2),
// the largest row-sum error max_i |sum_j F_ij - sum_j F_ref_ij| (cube: against 1), e_B = sqrt(sum_i A_i |B_i -
// B_ref_i|^2 / sum_i A_i |B_ref_i|^2) over the three channels, and CPU seconds of the form factors.
// Usage: bench_analytic [--k K] [--cornell-patches N] [--ref-rays R] [--scene PATH] [--skip-cornell]
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "bench_scene.h"
#include "core/parallel.h"
#include "formfactor/analytic_form_factors.h"
#include "formfactor/form_factors.h"
#include "patch/patch_builder.h"
#include "solve/direct_solver.h"
#include "solve/problem.h"
#include "support/box_scenes.h"
#include "support/view_factors.h"
#include "visibility/embree_visibility.h"

using namespace radwalk;
using radwalk::bench::cpu_seconds;

namespace {

struct Row {
  std::string method;
  double rms = 0, row_error = 0, e_B = 0, cpu = 0;
};

PatchRgb solve_B(const PatchSet& ps, const SparseF& F, const std::vector<std::size_t>& emitters) {
  RadiosityProblem p = make_problem(ps, F);
  if (!emitters.empty()) {
    p.E.setZero();
    for (std::size_t i : emitters) p.E.row(Eigen::Index(i)).setConstant(1.0);
  }
  return solve_direct(p).B;
}

double e_B(const PatchSet& ps, const PatchRgb& B, const PatchRgb& ref) {
  double num = 0, den = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    num += ps.area[i] * (B.row(Eigen::Index(i)) - ref.row(Eigen::Index(i))).square().sum();
    den += ps.area[i] * ref.row(Eigen::Index(i)).square().sum();
  }
  return std::sqrt(num / den);
}

// Per-pair RMS and the largest row-sum error of F against the dense reference (row-major N x N), rows_ref the
// reference row sums.
void compare(const SparseF& F, const std::vector<double>& ref, std::size_t N, const std::vector<double>& rows_ref,
             double& rms, double& row_error) {
  double sum2 = 0;
  std::size_t count = 0;
  row_error = 0;
  std::vector<double> dense(N);
  for (std::size_t i = 0; i < N; ++i) {
    std::fill(dense.begin(), dense.end(), 0.0);
    double row = 0;
    for (SparseF::InnerIterator it(F, Eigen::Index(i)); it; ++it) dense[std::size_t(it.col())] = it.value(), row += it.value();
    for (std::size_t j = 0; j < N; ++j) {
      const double r = ref[i * N + j];
      if (r == 0 && dense[j] == 0) continue;
      sum2 += (dense[j] - r) * (dense[j] - r);
      ++count;
    }
    row_error = std::max(row_error, std::abs(row - rows_ref[i]));
  }
  rms = std::sqrt(sum2 / double(std::max<std::size_t>(count, 1)));
}

std::vector<double> dense_of(const SparseF& F) {
  const std::size_t N = std::size_t(F.rows());
  std::vector<double> d(N * N, 0.0);
  for (std::size_t i = 0; i < N; ++i)
    for (SparseF::InnerIterator it(F, Eigen::Index(i)); it; ++it) d[i * N + std::size_t(it.col())] = it.value();
  return d;
}

void run_scene(const std::string& name, const PatchSet& ps, const std::vector<double>& ref,
               const std::vector<std::size_t>& emitters, const std::string& reference_note) {
  const std::size_t N = ps.size();
  std::vector<double> rows_ref(N, 0.0);
  for (std::size_t i = 0; i < N; ++i)
    for (std::size_t j = 0; j < N; ++j) rows_ref[i] += ref[i * N + j];
  SparseF Fref(static_cast<Eigen::Index>(N), static_cast<Eigen::Index>(N));
  {
    std::vector<Eigen::Triplet<float>> t;
    for (std::size_t i = 0; i < N; ++i)
      for (std::size_t j = 0; j < N; ++j)
        if (ref[i * N + j] != 0) t.emplace_back(int(i), int(j), float(ref[i * N + j]));
    Fref.setFromTriplets(t.begin(), t.end());
  }
  const PatchRgb Bref = solve_B(ps, Fref, emitters);
  const EmbreeVisibility vis(ps);
  std::vector<Row> rows;
  const auto measure = [&](const std::string& method, auto&& make) {
    const double t0 = cpu_seconds();
    const SparseF F = make();
    Row r;
    r.method = method;
    r.cpu = cpu_seconds() - t0;
    compare(F, ref, N, rows_ref, r.rms, r.row_error);
    r.e_B = e_B(ps, solve_B(ps, F, emitters), Bref);
    rows.push_back(r);
    std::fprintf(stderr, "  %s done\n", method.c_str());
  };
  measure("analytic", [&] { return analytic_form_factors(ps, vis).form_factors.F; });
  for (long rays : {1000L, 10000L})
    for (bool sobol : {false, true}) {
      FormFactorOptions o;
      o.rays_per_patch = rays;
      o.sobol = sobol;
      o.seed = 7;
      measure(std::string(sobol ? "sobol " : "stratified ") + std::to_string(rays) + " rays/patch",
              [&] { return estimate_form_factors(ps, vis, o).F; });
    }
  std::printf("\n%s: %zu patches; reference: %s\n", name.c_str(), N, reference_note.c_str());
  std::printf("%-30s %14s %14s %12s %10s\n", "method", "per-pair RMS", "row-sum error", "e_B", "CPU s");
  for (const Row& r : rows)
    std::printf("%-30s %14.3e %14.3e %12.3e %10.3f\n", r.method.c_str(), r.rms, r.row_error, r.e_B, r.cpu);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  int k = 13;
  std::size_t cornell_patches = 1000;
  long ref_rays = 1L << 17;
  std::string scene = bench::default_scene();
  bool cornell = true;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    const auto next = [&]() -> std::string {
      if (a + 1 >= argc) {
        std::fprintf(stderr, "bench_analytic: %s needs a value\n", arg.c_str());
        std::exit(2);
      }
      return argv[++a];
    };
    if (arg == "--k") k = std::stoi(next());
    else if (arg == "--cornell-patches") cornell_patches = std::stoul(next());
    else if (arg == "--ref-rays") ref_rays = std::stol(next());
    else if (arg == "--scene") scene = next();
    else if (arg == "--skip-cornell") cornell = false;
    else {
      std::fprintf(stderr, "bench_analytic: unknown option %s\n", arg.c_str());
      return 2;
    }
  }
  ThreadLimit one(1);
  std::printf("bench_analytic: one thread; CPU seconds of the form factors only\n");
  {
    const PatchSet ps = test::unit_cube_room(k);
    const std::size_t N = ps.size();
    std::vector<double> ref(N * N, 0.0);
    const auto rect = [&](std::size_t i) {
      test::AxisRectangle r;
      r.axis = std::abs(ps.normal[i].x()) > 0.5 ? 0 : std::abs(ps.normal[i].y()) > 0.5 ? 1 : 2;
      r.lo = r.hi = ps.corner(i, 0);
      for (int c = 1; c < 4; ++c) r.lo = r.lo.cwiseMin(ps.corner(i, c)), r.hi = r.hi.cwiseMax(ps.corner(i, c));
      r.plane = r.lo[r.axis];
      return r;
    };
    for (std::size_t i = 0; i < N; ++i)
      for (std::size_t j = 0; j < N; ++j) ref[i * N + j] = test::axis_rectangle_exchange_area(rect(i), rect(j)) / ps.area[i];
    std::vector<std::size_t> ceiling;  // the wall z = 1 (normal -z) emits
    for (std::size_t i = 0; i < N; ++i)
      if (ps.normal[i].z() < -0.5) ceiling.push_back(i);
    run_scene("cube " + std::to_string(k) + " x " + std::to_string(k) + " a wall", ps, ref, ceiling,
              "C-11 and C-14 by superposition, exact to ~1e-12 (stored in float for e_B)");
  }
  if (cornell) {
    const PatchSet ps = bench::patched_to(scene, cornell_patches, 0.1);
    const EmbreeVisibility vis(ps);
    FormFactorOptions o;
    o.rays_per_patch = ref_rays;
    o.sobol = true;
    o.seed = 1234;
    ThreadLimit all(0);
    const SparseF F = estimate_form_factors(ps, vis, o).F;
    const std::vector<double> ref = dense_of(F);
    double noise = 0;
    std::size_t count = 0;
    for (double f : ref)
      if (f > 0) noise += f * (1 - f) / double(ref_rays), ++count;
    noise = std::sqrt(noise / double(std::max<std::size_t>(count, 1)));
    ThreadLimit back(1);
    run_scene("cornell box", ps, ref, {},
              "Monte Carlo, Sobol, " + std::to_string(ref_rays) + " rays/patch (its own per-pair RMS noise ~" +
                  std::to_string(noise) + ")");
  }
  return 0;
}
