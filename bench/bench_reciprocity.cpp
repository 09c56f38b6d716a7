// bench_reciprocity: the form-factor diagnostics' reciprocity error and enforce_reciprocity, the transposed slabs
// (formfactor/transpose_slabs.h) against the former binary search of F_ji in row j per entry
// (tests/support/reciprocity_reference.h), side by side in one run on the same traced F, and checked equal bit
// for bit.
//
// Scene: meshes/cornell_box.obj patched to about each N of --sizes, F traced with --rays rays per patch. CPU
// seconds of the process (all threads): meaningful on a shared machine; each variant is timed --repeat times,
// the best kept.
// Usage: bench_reciprocity [--sizes 1e4,1e5] [--rays 100] [--repeat 2] [--enforce 1]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "bench_scene.h"
#include "core/parallel.h"
#include "formfactor/form_factor_diagnostics.h"
#include "formfactor/form_factors.h"
#include "formfactor/reciprocity.h"
#include "support/reciprocity_reference.h"
#include "visibility/embree_visibility.h"

using namespace radwalk;
using radwalk::bench::cpu_seconds;

namespace {

template <class F>
double best_cpu(int repeat, F&& f) {
  double best = 1e300;
  for (int r = 0; r < repeat; ++r) {
    const double c0 = cpu_seconds();
    f();
    best = std::min(best, cpu_seconds() - c0);
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<double> sizes = {1e4, 1e5};
  long rays = 100, repeat = 2, enforce = 1;
  for (int a = 1; a + 1 < argc; a += 2) {
    const std::string k = argv[a], v = argv[a + 1];
    if (k == "--sizes") {
      sizes.clear();
      std::stringstream in(v);
      for (std::string item; std::getline(in, item, ',');) sizes.push_back(std::atof(item.c_str()));
    } else if (k == "--rays") {
      rays = std::atol(v.c_str());
    } else if (k == "--repeat") {
      repeat = std::atol(v.c_str());
    } else if (k == "--enforce") {
      enforce = std::atol(v.c_str());
    } else {
      std::fprintf(stderr, "bench_reciprocity: unknown option %s\n", k.c_str());
      return 2;
    }
  }
  std::printf("bench_reciprocity: %d threads, %ld rays per patch; CPU seconds, best of %ld\n", active_threads(), rays,
              repeat);
  std::printf("%10s %12s %12s %12s %8s %12s %12s %8s %6s\n", "N", "nnz", "diag binsrch", "diag slabs", "ratio",
              "enf binsrch", "enf slabs", "ratio", "equal");
  for (const double target : sizes) {
    const PatchSet ps = bench::patched_to(bench::default_scene(), std::size_t(target), 0.05);
    const EmbreeVisibility vis(ps);
    FormFactorOptions o;
    o.rays_per_patch = rays;
    const FormFactors ff = estimate_form_factors(ps, vis, o);
    std::vector<double> old_err, new_err;
    const double t_old = best_cpu(int(repeat), [&] { old_err = test::binary_search_reciprocity_error(ff.F, ps.area); });
    const double t_new =
        best_cpu(int(repeat), [&] { new_err = diagnose_form_factors(ff.F, ps.area).reciprocity_error; });
    bool equal = old_err == new_err;
    double e_old = 0, e_new = 0;
    if (enforce) {
      SparseF a, b;
      ReciprocityChange ca, cb;
      e_old = best_cpu(int(repeat), [&] {
        a = ff.F;
        ca = test::binary_search_enforce_reciprocity(a, ps.area);
      });
      e_new = best_cpu(int(repeat), [&] {
        b = ff.F;
        cb = enforce_reciprocity(b, ps.area);
      });
      equal = equal && ca.mean_relative_change == cb.mean_relative_change &&
              ca.max_relative_change == cb.max_relative_change && a.nonZeros() == b.nonZeros() &&
              std::equal(a.valuePtr(), a.valuePtr() + a.nonZeros(), b.valuePtr()) &&
              std::equal(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros(), b.innerIndexPtr());
    }
    std::printf("%10zu %12ld %12.3f %12.3f %8.2f %12.3f %12.3f %8.2f %6s\n", ps.size(), long(ff.F.nonZeros()), t_old,
                t_new, t_old / t_new, e_old, e_new, e_new > 0 ? e_old / e_new : 0.0, equal ? "yes" : "NO");
    std::fflush(stdout);
  }
  return 0;
}
