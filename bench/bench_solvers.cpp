// bench_solvers: solve time and peak memory of each deterministic solver against patch count.
//
//   bench_solvers [--scene meshes/cornell_box.obj] [--max-edges 50,14,5] [--rays 1000]
//                 [--synthetic 1000,10000,100000] [--solvers direct-dense,direct-sparse,jacobi,gauss-seidel,
//                 southwell] [--tol 1e-10] [--max-direct 5000] [--max-shots-per-patch 100]
//
// By default the scene (the Cornell box) is patched at each --max-edges value (50, 14, 5 mm give about 1e3, 1e4,
// 1e5 patches) and F is estimated with `rays` rays per patch (Embree, all threads); the form-factor time is
// printed beside the solve times. --synthetic N,... uses solve/synthetic_problem.h instead (Monte Carlo-like rows,
// ~10 % escaping, Cornell-box materials). Each solve runs in a forked child, so its peak memory is measured alone:
// "extra MB" = peak resident size of the child minus its size at the fork (the problem itself, inherited, is the
// "F MB" column). Direct solvers are skipped above --max-direct patches (dense: N^2 doubles; sparse LU of a
// matrix with ~rays non-zeros per row fills in almost completely).
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bench_scene.h"
#include "core/timer.h"
#include "formfactor/form_factors.h"
#include "mesh/read_scene.h"
#include "patch/patching.h"
#include "visibility/embree_visibility.h"
#include "solve/solve_radiosity.h"
#include "solve/synthetic_problem.h"

using namespace radwalk;

namespace {

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');) out.push_back(item);
  return out;
}

long resident_kb() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmRSS:", 0) == 0) return std::atol(line.c_str() + 6);
  return 0;
}

struct Row {
  double seconds = 0, residual = 0, extra_mb = 0, condition = 0;
  long iterations = 0;
  char status[24] = {};
};

Row run(const std::string& solver, const RadiosityProblem& p, const SolveOptions& base, long shots_per_patch) {
  SolveOptions o = base;
  Solution s;
  const long start_kb = resident_kb();
  if (solver == "direct-dense") s = solve_direct(p, o, DirectMethod::dense);
  else if (solver == "direct-sparse") s = solve_direct(p, o, DirectMethod::sparse);
  else {
    o.solver = solver;
    if (solver == "southwell") o.max_iterations = shots_per_patch * long(p.size());
    s = solve_radiosity(p, o);
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  Row r;
  r.seconds = s.seconds;
  r.residual = s.residual;
  r.iterations = s.iterations;
  r.extra_mb = double(usage.ru_maxrss - start_kb) / 1024.0;
  r.condition = s.info.count("condition_estimate") ? s.info.at("condition_estimate") : 0;
  std::snprintf(r.status, sizeof r.status, "%s", to_string(s.status));
  return r;
}

// Runs one solve in a child process and reads its Row back through a pipe.
bool run_isolated(const std::string& solver, const RadiosityProblem& p, const SolveOptions& o, long shots,
                  Row& row) {
  int fds[2];
  if (pipe(fds) != 0) return false;
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    Row r = run(solver, p, o, shots);
    const ssize_t written = write(fds[1], &r, sizeof r);
    _exit(written == ssize_t(sizeof r) ? 0 : 1);
  }
  close(fds[1]);
  const ssize_t got = read(fds[0], &row, sizeof row);
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  return got == ssize_t(sizeof row) && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

// The problem of one size: the scene patched at max_edge with estimated F, or a synthetic one of n patches.
RadiosityProblem make_bench_problem(const std::string& scene, const std::string& size, bool synthetic, int rays,
                                    double& ff_seconds) {
  ff_seconds = 0;
  if (synthetic) return make_synthetic_problem(std::atol(size.c_str()), rays, 1);
  const PatchSet patches = make_patches(load_scene(scene), std::atof(size.c_str()));
  const EmbreeVisibility visibility(patches);
  FormFactorOptions o;
  o.rays_per_patch = rays;
  Timer t;
  FormFactors ff = estimate_form_factors(patches, visibility, o);
  ff_seconds = t.seconds();
  return make_problem(patches, std::move(ff.F));
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene = bench::default_scene();
  std::vector<std::string> sizes = {"50", "14", "5"};
  bool synthetic = false;
  std::vector<std::string> solvers = {"direct-dense", "direct-sparse", "jacobi", "gauss-seidel", "southwell"};
  int rays = 1000;
  long max_direct = 5000, shots_per_patch = 100;
  SolveOptions options;
  for (int a = 1; a + 1 < argc; a += 2) {
    const std::string key = argv[a], value = argv[a + 1];
    if (key == "--max-edges") {
      sizes = split(value);
      synthetic = false;
    } else if (key == "--synthetic") {
      sizes = split(value);
      synthetic = true;
    } else if (key == "--scene") scene = value;
    else if (key == "--solvers") solvers = split(value);
    else if (key == "--rays") rays = std::atoi(value.c_str());
    else if (key == "--tol") options.tol = std::atof(value.c_str());
    else if (key == "--max-direct") max_direct = std::atol(value.c_str());
    else if (key == "--max-shots-per-patch") shots_per_patch = std::atol(value.c_str());
    else {
      std::fprintf(stderr, "unknown option %s\n", key.c_str());
      return 2;
    }
  }
  std::printf("# %s F (%d rays per patch), tol %g, %s\n", synthetic ? "synthetic" : scene.c_str(), rays,
              options.tol, "times are the solve alone; extra MB = peak RSS of the solve's child process above F");
  std::printf("%8s %10s %7s %-14s %10s %9s %10s %-15s %10s %9s\n", "N", "nnz(F)", "F MB", "solver", "seconds",
              "iters", "residual", "status", "kappa_inf", "extra MB");
  for (const auto& size : sizes) {
    double ff_seconds = 0;
    Timer t;
    const RadiosityProblem p = make_bench_problem(scene, size, synthetic, rays, ff_seconds);
    const long n = static_cast<long>(p.size());
    const double build = t.seconds();
    const double f_mb = double(p.F.nonZeros()) * 8.0 / (1 << 20);
    if (synthetic)
      std::printf("# N = %ld: synthetic F built in %.2f s\n", n, build);
    else
      std::printf("# N = %ld (max edge %s): load + patch + F in %.2f s, of which form factors %.2f s (%.2f Mrays/s)\n",
                  n, size.c_str(), build, ff_seconds, double(n) * rays / std::max(ff_seconds, 1e-9) / 1e6);
    for (const auto& solver : solvers) {
      if (solver.rfind("direct", 0) == 0 && n > max_direct) {
        std::printf("%8ld %10ld %7.1f %-14s %10s (skipped: N > --max-direct %ld)\n", n, long(p.F.nonZeros()), f_mb,
                    solver.c_str(), "-", max_direct);
        continue;
      }
      Row r;
      if (!run_isolated(solver, p, options, shots_per_patch, r)) {
        std::printf("%8ld %10ld %7.1f %-14s failed (child process)\n", n, long(p.F.nonZeros()), f_mb,
                    solver.c_str());
        continue;
      }
      std::printf("%8ld %10ld %7.1f %-14s %10.4f %9ld %10.2e %-15s %10.4g %9.1f\n", n, long(p.F.nonZeros()), f_mb,
                  solver.c_str(), r.seconds, r.iterations, r.residual, r.status, r.condition, r.extra_mb);
      std::fflush(stdout);
    }
  }
  return 0;
}
