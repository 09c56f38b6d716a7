// bench_solvers: solve time and peak memory of each deterministic solver against patch count.
//
//   bench_solvers [--sizes 1000,10000,100000] [--rays 1000] [--solvers direct-dense,direct-sparse,jacobi,
//                 gauss-seidel,southwell] [--tol 1e-10] [--max-direct 5000] [--max-shots-per-patch 100]
//
// F is SYNTHETIC (solve/synthetic_problem.h: Monte Carlo-like rows, `rays` rays per patch, ~10 % escaping,
// Cornell-box materials), not the Cornell box with estimated form factors: the form-factor layer did not build
// when this was written, so no form-factor time is printed. Each solve runs in a forked child, so its peak memory
// is measured alone: "extra MB" = peak resident size of the child minus its size at the fork (the problem itself,
// inherited, is the "F MB" column). Direct solvers are skipped above --max-direct patches (dense: N^2 doubles;
// sparse LU of a matrix with ~rays non-zeros per row fills in almost completely).
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/timer.h"
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

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> sizes = {"1000", "10000", "100000"};
  std::vector<std::string> solvers = {"direct-dense", "direct-sparse", "jacobi", "gauss-seidel", "southwell"};
  int rays = 1000;
  long max_direct = 5000, shots_per_patch = 100;
  SolveOptions options;
  for (int a = 1; a + 1 < argc; a += 2) {
    const std::string key = argv[a], value = argv[a + 1];
    if (key == "--sizes") sizes = split(value);
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
  std::printf("# synthetic F (%d rays per patch), tol %g, %s\n", rays, options.tol,
              "times are the solve alone; extra MB = peak RSS of the solve's child process above the problem");
  std::printf("%8s %10s %7s %-14s %10s %9s %10s %-15s %10s %9s\n", "N", "nnz(F)", "F MB", "solver", "seconds",
              "iters", "residual", "status", "kappa_inf", "extra MB");
  for (const auto& size : sizes) {
    const long n = std::atol(size.c_str());
    Timer t;
    const RadiosityProblem p = make_synthetic_problem(n, rays, 1);
    const double build = t.seconds();
    const double f_mb = double(p.F.nonZeros()) * 8.0 / (1 << 20);
    std::fprintf(stderr, "N = %ld: synthetic F built in %.2f s\n", n, build);
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
