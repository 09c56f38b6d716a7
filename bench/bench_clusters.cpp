// bench_clusters: the cost of the hierarchical stochastic Jacobi to a fixed error as the faces of a generated city
// block (bench/city_block.h) grow tenfold, without and with oriented clusters (hierarchy/cluster_tree.h). Not a test.
//
//   bench_clusters [--cells 4.2,1.34,0.42] [--rays-per-face 20] [--ref-factor 16] [--ratio 0.25] [--targets 0.1,0.05]
//                  [--points 3] [--threads T]
//
// Per cell size (faces ~ 1.8e5 / cell^2): the faces are the leaves (no element refinement: both oracles off, so
// only clustering differs), the direct light D from --points^2 points per face, the same D (one seed) in every run.
// Reference: the solver without clusters at --ref-factor x 4 x --rays-per-face rays a face, another seed: it is
// unbiased for the faces' discrete system, the answer both runs are after (the faces' own discretisation error
// against the continuous solution is the same for both and not clustering's business).
// Error: of the indirect light I = B - E - D per face, e = sqrt((sum_i A_i |I_i - I_ref_i|^2 - sum_i A_i se_ref_i^2)
// / sum_i A_i |I_ref_i|^2) over the three channels, the reference's own noise (its replicate standard errors se_ref)
// taken out. Each configuration runs at n1 = rays-per-face x faces and n2 = 4 n1 rays; e^2 = b^2 + a / n fitted
// through the two (b: the bias, a / n: the noise), the CPU time as t = t0 + n t_ray; the cost to a target error T is
// n* = a / (T^2 - b^2) rays (none if b >= T) and t0 + n* t_ray CPU seconds (all threads; the process's CPU clock).
// Then the exponents k of cost ~ faces^k between successive sizes and by least squares.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "bench_scene.h"
#include "city_block.h"
#include "core/parallel.h"
#include "hierarchy/hierarchical_jacobi.h"
#include "visibility/embree_visibility.h"

using namespace radwalk;
using radwalk::bench::cpu_seconds;

namespace {

std::vector<double> parse_list(const char* s) {
  std::vector<double> v;
  std::stringstream in(s);
  std::string x;
  while (std::getline(in, x, ',')) v.push_back(std::stod(x));
  return v;
}

struct Run {
  double error = 0, noise = 0, seconds = 0;
  long rays = 0;
  std::size_t clusters = 0, memory = 0;
  long deposits = 0;
};

PatchRgb indirect(const PatchSet& ps, const HierarchicalResult& r) {
  PatchRgb I = r.B - r.D;
  for (Eigen::Index k = 0; k < I.rows(); ++k)
    I.row(k) -= ps.E[static_cast<std::size_t>(r.tree.root[static_cast<std::size_t>(r.leaves[static_cast<std::size_t>(k)])])]
                    .transpose();
  return I;
}

// The relative L2 error of run r's indirect light against the reference's, the reference's noise taken out.
Run measure(const PatchSet& ps, const HierarchicalResult& r, const PatchRgb& Iref, const PatchRgb& ref_se2,
            double seconds) {
  const PatchRgb I = indirect(ps, r);
  double num = 0, den = 0;
  for (Eigen::Index k = 0; k < I.rows(); ++k) {
    const double A = ps.area[static_cast<std::size_t>(k)];
    num += A * ((I.row(k) - Iref.row(k)).square().sum() - ref_se2.row(k).sum());
    den += A * Iref.row(k).square().sum();
  }
  Run m;
  m.error = std::sqrt(std::max(0.0, num) / den);
  m.seconds = seconds;
  m.rays = r.rays;
  m.clusters = r.clusters;
  m.memory = r.memory_bytes;
  m.deposits = r.cluster_deposits;
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<double> cells = {4.2, 1.34, 0.42}, targets = {0.1, 0.05};
  double rays_per_face = 20, ref_factor = 16, ratio = 0.25;
  int points = 3, threads = 0;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--cells")) cells = parse_list(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--targets")) targets = parse_list(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--rays-per-face")) rays_per_face = std::stod(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--ref-factor")) ref_factor = std::stod(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--ratio")) ratio = std::stod(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--points")) points = std::stoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--threads")) threads = std::stoi(argv[i + 1]);
    else {
      std::fprintf(stderr, "bench_clusters: unknown option %s\n", argv[i]);
      return 2;
    }
  }
  const ThreadLimit limit(threads);
  std::printf("# bench_clusters: ratio %.3g, %.3g rays a face and 4x that, reference %.3g x 4 x that, %d^2 points "
              "a face for D\n",
              ratio, rays_per_face, ref_factor, points);
  std::printf("%9s %7s %8s %11s %9s %9s %9s %9s %8s", "faces", "clust", "cl_nodes", "rays", "cpu_s", "err", "bias",
              "noise_n1", "dep_frac");
  for (const double T : targets) std::printf("  rays@%-5.3g  cpu@%-5.3g", T, T);
  std::printf("\n");
  std::vector<double> faces;
  std::vector<std::vector<std::vector<double>>> cost(2);  // [clusters][size][target] CPU seconds (NaN: not reached)
  for (const double cell : cells) {
    const PatchSet ps = bench::city_block(cell);
    const EmbreeVisibility visibility(ps);
    const auto N = static_cast<double>(ps.size());
    faces.push_back(N);
    HierarchicalOptions base;
    base.direct_oracle = base.transport_oracle = false;
    base.points_side = points;
    base.replicates = 4;
    base.particles = static_cast<long>(ref_factor * 4 * rays_per_face * N);
    base.seed = 1001;
    base.direct_seed = 1001;  // one D for every run: the errors are those of the indirect light alone
    base.replicates = 32;     // the reference's rays in 32 replicates: one iteration's ray records stay small
    const HierarchicalResult ref = solve_hierarchical(ps, visibility, base);
    const PatchRgb Iref = indirect(ps, ref);
    const PatchRgb ref_se2 = ref.var / static_cast<double>(base.particles);
    for (int cl = 0; cl < 2; ++cl) {
      std::vector<Run> runs;
      for (const double mult : {1.0, 4.0}) {
        HierarchicalOptions o = base;
        o.seed = 7;
        o.replicates = 4;
        o.clusters = cl == 1;
        o.cluster_ratio = ratio;
        o.particles = static_cast<long>(mult * rays_per_face * N);
        const double t0 = cpu_seconds();
        const HierarchicalResult r = solve_hierarchical(ps, visibility, o);
        runs.push_back(measure(ps, r, Iref, ref_se2, cpu_seconds() - t0));
      }
      const double n1 = runs[0].rays, n2 = runs[1].rays;
      const double e1 = runs[0].error * runs[0].error, e2 = runs[1].error * runs[1].error;
      const double a = std::max(0.0, (e1 - e2) / (1 / n1 - 1 / n2));
      const double b2 = std::max(0.0, e1 - a / n1);
      const double t_ray = (runs[1].seconds - runs[0].seconds) / (n2 - n1);
      const double t0 = std::max(0.0, runs[0].seconds - t_ray * n1);
      for (int q = 0; q < 2; ++q) {
        const Run& m = runs[static_cast<std::size_t>(q)];
        std::printf("%9.0f %7s %8zu %11ld %9.2f %9.4f %9.4f %9.4f %8.3f", N, cl ? "on" : "off", m.clusters, m.rays,
                    m.seconds, m.error, std::sqrt(b2), std::sqrt(a / n1),
                    m.rays > 0 ? static_cast<double>(m.deposits) / static_cast<double>(m.rays) : 0.0);
        if (q == 1) {
          std::vector<double> c;
          for (const double T : targets) {
            const double ns = T * T > b2 ? a / (T * T - b2) : NAN;
            const double cs = std::isfinite(ns) ? t0 + ns * t_ray : NAN;
            c.push_back(cs);
            std::printf("  %11.3g %10.3g", ns, cs);
          }
          cost[static_cast<std::size_t>(cl)].push_back(c);
        }
        std::printf("\n");
      }
    }
    std::fflush(stdout);
  }
  // Exponents of cost ~ faces^k.
  for (int cl = 0; cl < 2; ++cl)
    for (std::size_t t = 0; t < targets.size(); ++t) {
      std::printf("clusters %-3s target %-5.3g exponents:", cl ? "on" : "off", targets[t]);
      double sx = 0, sy = 0, sxx = 0, sxy = 0;
      int m = 0;
      for (std::size_t s = 0; s < faces.size(); ++s) {
        const double c = cost[static_cast<std::size_t>(cl)][s][t];
        if (s > 0) {
          const double p = cost[static_cast<std::size_t>(cl)][s - 1][t];
          std::printf(" %.2f", std::log(c / p) / std::log(faces[s] / faces[s - 1]));
        }
        if (std::isfinite(c) && c > 0) {
          const double x = std::log(faces[s]), y = std::log(c);
          sx += x, sy += y, sxx += x * x, sxy += x * y, ++m;
        }
      }
      if (m >= 2) std::printf("  least squares %.2f", (m * sxy - sx * sy) / (m * sxx - sx * sx));
      std::printf("\n");
    }
  return 0;
}
