// Hierarchical stochastic Jacobi (hierarchy/hierarchical_jacobi.h) against uniform patching, at their measured
// error against the path tracer: elements, CPU seconds and error side by side. A benchmark, not a test.
//
// Error measure (as scripts/experiments/adaptive_patching.py): the path tracer's patch averages B_ref on a fine
// uniform grid (--ref-max-edge, --ref-spp samples per cell, seed + 1000), each fine cell given the value of the
// mesh patch (same input face) that contains its centroid; over the cells that are neither hidden (B_ref = 0) nor
// emitting, area-weighted over cells and channels,
//   raw^2 = sum A (B_mesh - B_ref)^2 / sum A B_ref^2,  noise^2 = sum A se_ref^2 / sum A B_ref^2,
//   error = sqrt(max(raw^2 - noise^2, 0)),
// the relative L2 distance of the piecewise-constant solution from the continuous one (its statistical noise
// included). CPU seconds: the process's CPU time of the solve alone (form factors and solve for uniform patching:
// cosine rays with the emitter columns exact, the recommended route, then the auto solver; the whole
// hierarchical solve), all threads together.
//
// Usage: bench_hierarchical [SCENE] [--ref-max-edge L] [--ref-spp N] [--max-edges 0,100,50] [--ff-rays N]
//                           [--tols 0.01,0.003] [--rays N] [--levels L] [--seed S]
//                           [--ref-cache FILE] [--budgets 300,1000] [--share 0.5] [--rays-per-leaf N] [--oracles]
//                           [--final-rays-per-leaf N] [--per-material] [--target E]
// (--target: the budget rows also stop once the estimated relative error is at most E.)
// (--final-rays-per-leaf: the final solve of a budget gets N x the budget rays instead of --rays.)
// --budgets: refinement by the estimate (hierarchy/estimate_refinement.h) up to each budget of leaves, from the
// input faces, with the a-priori oracles off (--oracles: on, at the first of --tols).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "bench_scene.h"
#include "formfactor/emitter_form_factors.h"
#include "hierarchy/estimate_refinement.h"
#include "hierarchy/hierarchical_jacobi.h"
#include "hierarchy/leaf_patches.h"
#include "pathtrace/patch_average.h"
#include "solve/problem.h"
#include "solve/solve_radiosity.h"
#include "visibility/embree_visibility.h"

using namespace radwalk;

namespace {

std::vector<double> numbers(const std::string& s) {
  std::vector<double> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(std::atof(item.c_str()));
  return out;
}

// Signed distance of p inside the convex polygon (positive inside), about normal n.
double inside(const std::array<Vec3, 4>& c, int k, const Vec3& p, const Vec3& n) {
  double d = 1e300;
  for (int a = 0; a < k; ++a) {
    const Vec3 e = c[static_cast<std::size_t>((a + 1) % k)] - c[static_cast<std::size_t>(a)];
    d = std::min(d, e.cross(p - c[static_cast<std::size_t>(a)]).dot(n) / e.norm());
  }
  return d;
}

struct Reference {
  PatchSet cells;
  PatchRgb B, B_se;
  std::vector<char> keep;
  double norm = 0, noise2 = 0;
};

bool per_material = false;

// The error of a piecewise-constant solution whose value at a point p of input face f is value(f, p).
template <class Value>
double error_of(const Reference& ref, Value&& value, double* raw = nullptr) {
  double r2 = 0;
  for (std::size_t i = 0; i < ref.cells.size(); ++i) {
    if (!ref.keep[i]) continue;
    const Rgb b = value(static_cast<std::size_t>(ref.cells.face[i]), ref.cells.centroid[i]);
    r2 += ref.cells.area[i] * (b - ref.B.row(static_cast<Eigen::Index>(i)).transpose()).square().sum();
  }
  r2 /= ref.norm;
  if (raw) *raw = std::sqrt(r2);
  if (per_material) {
    // Per material: the relative difference of the area-weighted means over the kept cells (all channels
    // together), with the reference's own relative standard error.
    std::vector<double> a(ref.cells.materials.size(), 0), m(a.size(), 0), mr(a.size(), 0), v(a.size(), 0);
    for (std::size_t i = 0; i < ref.cells.size(); ++i) {
      if (!ref.keep[i]) continue;
      const auto k = static_cast<std::size_t>(ref.cells.material[i]);
      const Rgb b = value(static_cast<std::size_t>(ref.cells.face[i]), ref.cells.centroid[i]);
      const double A = ref.cells.area[i];
      a[k] += A;
      m[k] += A * b.sum();
      mr[k] += A * ref.B.row(static_cast<Eigen::Index>(i)).sum();
      v[k] += A * A * ref.B_se.row(static_cast<Eigen::Index>(i)).square().sum();
    }
    std::printf("    per material (mean - reference) / reference, +- the reference's se:");
    for (std::size_t k = 0; k < a.size(); ++k)
      if (mr[k] > 0)
        std::printf(" %s %+.1f%% (+-%.1f)", ref.cells.materials[k].name.c_str(), 100 * (m[k] - mr[k]) / mr[k],
                    100 * std::sqrt(v[k]) / mr[k]);
    std::printf("\n");
  }
  return std::sqrt(std::max(r2 - ref.noise2, 0.0));
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene = bench::default_scene();
  double ref_edge = 10;
  long ref_spp = 256, ff_rays = 4000, rays = 2'000'000;
  int levels = 8;
  std::uint64_t seed = 1;
  std::vector<double> edges = {0, 100, 50, 35, 25}, tols = {0.01, 0.003, 0.001, 0.0003}, budgets;
  double share = 0.5;
  long rays_per_leaf = 2000, final_rays_per_leaf = 0;
  bool oracles = false;
  std::string ref_cache;
  double target = 0;
  for (int a = 1; a < argc; ++a) {
    const std::string k = argv[a];
    const auto next = [&] { return std::string(a + 1 < argc ? argv[++a] : ""); };
    if (k == "--ref-max-edge") ref_edge = std::atof(next().c_str());
    else if (k == "--ref-spp") ref_spp = std::atol(next().c_str());
    else if (k == "--max-edges") edges = numbers(next());
    else if (k == "--ff-rays") ff_rays = std::atol(next().c_str());
    else if (k == "--tols") tols = numbers(next());
    else if (k == "--rays") rays = std::atol(next().c_str());
    else if (k == "--levels") levels = std::atoi(next().c_str());
    else if (k == "--ref-cache") ref_cache = next();
    else if (k == "--budgets") budgets = numbers(next());
    else if (k == "--share") share = std::atof(next().c_str());
    else if (k == "--rays-per-leaf") rays_per_leaf = std::atol(next().c_str());
    else if (k == "--oracles") oracles = true;
    else if (k == "--per-material") per_material = true;
    else if (k == "--target") target = std::atof(next().c_str());
    else if (k == "--final-rays-per-leaf") final_rays_per_leaf = std::atol(next().c_str());
    else if (k == "--seed") seed = std::strtoull(next().c_str(), nullptr, 10);
    else if (!k.empty() && k[0] != '-') scene = k;
    else {
      std::fprintf(stderr, "bench_hierarchical: unknown option %s\n", k.c_str());
      return 2;
    }
  }
  const Mesh mesh = load_scene(scene);
  Reference ref;
  ref.cells = make_patches(mesh, ref_edge);
  {
    const EmbreeVisibility vis(ref.cells);
    PatchAverageOptions o;
    o.spp = ref_spp;
    o.seed = seed + 1000;
    o.progress = false;
    // --ref-cache FILE: the reference's B and B_se kept between runs (read when the file holds as many cells).
    Solution s;
    bool cached = false;
    if (!ref_cache.empty()) {
      if (std::FILE* f = std::fopen(ref_cache.c_str(), "rb")) {
        long n = 0;
        if (std::fread(&n, sizeof n, 1, f) == 1 && n == static_cast<long>(ref.cells.size())) {
          s.B.resize(n, 3);
          s.B_se.resize(n, 3);
          cached = std::fread(s.B.data(), sizeof(double), static_cast<std::size_t>(3 * n), f) == static_cast<std::size_t>(3 * n) &&
                   std::fread(s.B_se.data(), sizeof(double), static_cast<std::size_t>(3 * n), f) == static_cast<std::size_t>(3 * n);
        }
        std::fclose(f);
      }
    }
    if (!cached) {
      s = estimate_patch_averages(ref.cells, vis, o);
      if (!ref_cache.empty())
        if (std::FILE* f = std::fopen(ref_cache.c_str(), "wb")) {
          const long n = static_cast<long>(ref.cells.size());
          std::fwrite(&n, sizeof n, 1, f);
          std::fwrite(s.B.data(), sizeof(double), static_cast<std::size_t>(3 * n), f);
          std::fwrite(s.B_se.data(), sizeof(double), static_cast<std::size_t>(3 * n), f);
          std::fclose(f);
        }
    }
    ref.B = s.B;
    ref.B_se = s.B_se;
    ref.keep.resize(ref.cells.size());
    for (std::size_t i = 0; i < ref.cells.size(); ++i) {
      const auto r = static_cast<Eigen::Index>(i);
      ref.keep[i] = (s.B.row(r) > 0).any() && (ref.cells.E[i] == 0).all();
      if (!ref.keep[i]) continue;
      ref.norm += ref.cells.area[i] * s.B.row(r).square().sum();
      ref.noise2 += ref.cells.area[i] * s.B_se.row(r).square().sum();
    }
    ref.noise2 /= ref.norm;
  }
  std::printf("scene %s\nreference: %zu cells (max edge %g), %ld samples each, relative noise %.4f\n", scene.c_str(),
              ref.cells.size(), ref_edge, ref_spp, std::sqrt(ref.noise2));
  std::printf("%-14s %10s %10s %10s %10s %10s\n", "method", "param", "elements", "cpu_s", "error", "raw_error");

  for (const double L : edges) {
    const PatchSet p = make_patches(mesh, L);
    const double t0 = bench::cpu_seconds();
    const EmbreeVisibility vis(p);
    FormFactorOptions o;
    o.rays_per_patch = ff_rays;
    o.seed = seed;
    EmitterFormFactors ff = estimate_emitter_form_factors(p, vis, o, 64);
    const RadiosityProblem problem = make_problem(p, std::move(ff.form_factors.F));
    const Solution s = solve_radiosity(problem);
    const double cpu = bench::cpu_seconds() - t0;
    std::vector<std::vector<std::size_t>> of_face;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const auto f = static_cast<std::size_t>(p.face[i]);
      if (of_face.size() <= f) of_face.resize(f + 1);
      of_face[f].push_back(i);
    }
    double raw = 0;
    const double err = error_of(
        ref,
        [&](std::size_t f, const Vec3& x) {
          std::size_t best = of_face[f].front();
          double best_in = -1e300;
          for (const std::size_t i : of_face[f]) {
            std::array<Vec3, 4> c;
            for (int k = 0; k < p.corner_count(i); ++k) c[static_cast<std::size_t>(k)] = p.corner(i, k);
            const double d = inside(c, p.corner_count(i), x, p.normal[i]);
            if (d > best_in) {
              best_in = d;
              best = i;
            }
          }
          return Rgb(s.B.row(static_cast<Eigen::Index>(best)).transpose());
        },
        &raw);
    std::printf("%-14s %10g %10zu %10.2f %10.4f %10.4f\n", "uniform", L, p.size(), cpu, err, raw);
    std::fflush(stdout);
  }

  const PatchSet roots = make_patches(mesh, 0);
  // The roots of each input face (a polygon triangulated into several patches has several), and the one whose
  // polygon holds a point best (as for the uniform patches above).
  std::vector<std::vector<std::size_t>> roots_of_face;
  for (std::size_t i = 0; i < roots.size(); ++i) {
    const auto f = static_cast<std::size_t>(roots.face[i]);
    if (roots_of_face.size() <= f) roots_of_face.resize(f + 1);
    roots_of_face[f].push_back(i);
  }
  const auto root_at = [&](std::size_t f, const Vec3& x) {
    std::size_t best = roots_of_face[f].front();
    double best_in = -1e300;
    for (const std::size_t i : roots_of_face[f]) {
      std::array<Vec3, 4> c;
      for (int k = 0; k < roots.corner_count(i); ++k) c[static_cast<std::size_t>(k)] = roots.corner(i, k);
      const double d = inside(c, roots.corner_count(i), x, roots.normal[i]);
      if (d > best_in) {
        best_in = d;
        best = i;
      }
    }
    return best;
  };
  const auto error_of_leaves = [&](const HierarchicalResult& h, double* raw) {
    std::vector<Eigen::Index> row(h.tree.size(), -1);
    for (std::size_t k = 0; k < h.leaves.size(); ++k) row[static_cast<std::size_t>(h.leaves[k])] = static_cast<Eigen::Index>(k);
    return error_of(
        ref,
        [&](std::size_t f, const Vec3& x) {
          std::size_t e = root_at(f, x);
          const Vec3& n = roots.normal[e];
          while (!h.tree.is_leaf(e)) e = static_cast<std::size_t>(h.tree.child_containing(e, x, n));
          return Rgb(h.B.row(row[e]).transpose());
        },
        raw);
  };
  for (const double budget : budgets) {
    const double t0 = bench::cpu_seconds();
    const EmbreeVisibility vis(roots);
    HierarchicalOptions o;
    o.tol = tols.empty() ? 1e-3 : tols.front();
    o.max_level = levels;
    o.particles = final_rays_per_leaf > 0 ? static_cast<long>(final_rays_per_leaf * budget) : rays;
    o.seed = seed;
    o.direct_oracle = o.transport_oracle = oracles;
    EstimateRefinementOptions e;
    e.steps = 40;
    e.max_leaves = static_cast<long>(budget);
    e.target = target;
    e.split_share = share;
    e.rays_per_leaf = rays_per_leaf;
    const EstimateRefinementResult r = refine_by_estimate(roots, vis, o, e);
    const double cpu = bench::cpu_seconds() - t0;
    double raw = 0;
    const double err = error_of_leaves(r.solution, &raw);
    EstimateRefinementStep last_estimate = r.steps.back();  // the last step with an estimate
    for (const EstimateRefinementStep& st : r.steps)
      if (std::isfinite(st.eta)) last_estimate = st;
    for (const EstimateRefinementStep& st : r.steps)
      std::printf("    step: %ld leaves, eta %.4f, split %ld, %.2f s (estimate %.2f s)\n", st.leaves, st.eta, st.split,
                  st.seconds, st.estimate_seconds);
    std::printf("%-14s %10g %10zu %10.2f %10.4f %10.4f   (%zu steps; estimated eta at the last: %.4f, B_disc share "
                "%.2f)\n",
                "h-estimate", budget, r.solution.leaves.size(), cpu, err, raw, r.steps.size(), last_estimate.eta,
                last_estimate.disc_share);
    std::fflush(stdout);
  }
  for (const double tol : budgets.empty() ? tols : std::vector<double>{}) {
    const double t0 = bench::cpu_seconds();
    const EmbreeVisibility vis(roots);
    HierarchicalOptions o;
    o.tol = tol;
    o.max_level = levels;
    o.particles = rays;
    o.seed = seed;
    const HierarchicalResult h = solve_hierarchical(roots, vis, o);
    const double cpu = bench::cpu_seconds() - t0;
    std::vector<Eigen::Index> row(h.tree.size(), -1);
    for (std::size_t k = 0; k < h.leaves.size(); ++k) row[static_cast<std::size_t>(h.leaves[k])] = static_cast<Eigen::Index>(k);
    double raw = 0;
    const double err = error_of(
        ref,
        [&](std::size_t f, const Vec3& x) {
          std::size_t e = root_at(f, x);
          const Vec3& n = roots.normal[e];
          while (!h.tree.is_leaf(e)) e = static_cast<std::size_t>(h.tree.child_containing(e, x, n));
          return Rgb(h.B.row(row[e]).transpose());
        },
        &raw);
    std::printf("%-14s %10g %10zu %10.2f %10.4f %10.4f   (%zu elements, %d levels, %ld direct + %ld transport splits)\n",
                "hierarchical", tol, h.leaves.size(), cpu, err, raw, h.tree.size(), h.tree.depth() + 1,
                h.direct_splits, h.transport_splits);
    std::fflush(stdout);
  }
  return 0;
}
