#include "solve/jacobi.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/parallel.h"
#include "core/timer.h"
#include "solve/convergence.h"
#include "solve/distributed_sweeps.h"
#include "solve/residual.h"

namespace radwalk {

Solution solve_jacobi(const RadiosityProblem& p, const SolveOptions& options) {
  check_problem(p);
  check_options(options);
  Timer timer;
  Solution s;
  s.method = "jacobi";
  const StabilityCheck check = check_stability(p, options, s.method, 1.0);
  record_stability(check, s);

  const PatchRgb D = system_diagonal(p);
  const Rgb scale = residual_scale(p.E);
  PatchRgb B = p.E / D, next(B.rows(), 3);
  if (!check.ok) {
    finish_iterative(s, p, options, std::move(B), refusal(check), check.message, 0, {}, "sweeps");
    s.seconds = timer.seconds();
    return s;
  }

  // Over MPI a rank sweeps its block of rows, then the ranks exchange them (distributed_sweeps.h).
  const std::vector<distributed::Range> blocks = sweep_row_blocks(p);
  const distributed::Range mine = blocks[static_cast<std::size_t>(distributed::rank())];
  run_sweeps(s, p, options, std::move(B), [&](PatchRgb& B) {
    // One sweep; the largest |r_ic| / scale_c of B^k comes out of it.
    const double r = deterministic_reduce(
        mine.size(), 256, 0.0,
        [&](std::size_t b, std::size_t e) {
          double worst = 0;
          for (std::size_t k = mine.begin + b; k < mine.begin + e; ++k) {
            const auto i = Eigen::Index(k);
            double s0 = 0, s1 = 0, s2 = 0;
            for (SparseF::InnerIterator it(p.F, i); it; ++it) {
              if (it.col() == i) continue;
              const double f = it.value();
              s0 += f * B(it.col(), 0);
              s1 += f * B(it.col(), 1);
              s2 += f * B(it.col(), 2);
            }
            const double sum[3] = {s0, s1, s2};
            for (int c = 0; c < 3; ++c) {
              next(i, c) = (p.E(i, c) + p.rho(i, c) * sum[c]) / D(i, c);
              const double ri = std::abs(D(i, c) * (next(i, c) - B(i, c))) / scale(c);
              worst = std::isnan(ri) || std::isnan(worst) ? std::numeric_limits<double>::quiet_NaN()
                                                          : std::max(worst, ri);
            }
          }
          return worst;
        },
        [](double a, double b) { return std::isnan(a) || std::isnan(b) ? a + b : std::max(a, b); });
    exchange_rows(next, blocks);
    std::swap(B, next);
    return distributed::max_over_ranks(r);
  });
  s.seconds = timer.seconds();
  return s;
}

}  // namespace radwalk
