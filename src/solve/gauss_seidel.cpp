#include "solve/gauss_seidel.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/timer.h"
#include "solve/convergence.h"
#include "solve/distributed_sweeps.h"
#include "solve/residual.h"

namespace radwalk {

Solution solve_gauss_seidel(const RadiosityProblem& p, const SolveOptions& options) {
  check_problem(p);
  check_options(options);
  Timer timer;
  Solution s;
  s.method = "gauss-seidel";
  // Rate factor 0.5: Gauss-Seidel on a consistently ordered matrix squares the Jacobi rate (optimistic side).
  const StabilityCheck check = check_stability(p, options, s.method, 0.5);
  record_stability(check, s);

  const Eigen::Index n = Eigen::Index(p.size());
  const PatchRgb D = system_diagonal(p);
  const Rgb scale = residual_scale(p.E);
  PatchRgb B = p.E / D, dB = PatchRgb::Zero(n, 3);
  if (!check.ok) {
    finish_iterative(s, p, options, std::move(B), refusal(check), check.message, 0, {}, "sweeps");
    s.seconds = timer.seconds();
    return s;
  }

  // Over MPI a rank sweeps its block of rows in order, using the other blocks' B of the previous sweep, then the
  // ranks exchange their rows (distributed_sweeps.h): block Gauss-Seidel within a rank, Jacobi between ranks.
  // The splitting is then M = D - L_b (L_b: the strict lower triangle of H inside the diagonal blocks), and the
  // residual r(B^k) = M (B^{k+1} - B^k) takes the lower sum over j in the own block only: still exact.
  const std::vector<distributed::Range> blocks = sweep_row_blocks(p);
  const distributed::Range mine = blocks[static_cast<std::size_t>(distributed::rank())];
  const auto first = Eigen::Index(mine.begin), end = Eigen::Index(mine.end);
  run_sweeps(s, p, options, std::move(B), [&](PatchRgb& B) {
    // One sweep in patch order; r accumulates max_i |r_ic(B^k)| / scale_c.
    double r = 0;
    bool finite = true;
    for (Eigen::Index i = first; i < end; ++i) {
      double s0 = 0, s1 = 0, s2 = 0, l0 = 0, l1 = 0, l2 = 0;
      for (SparseF::InnerIterator it(p.F, i); it; ++it) {
        const auto j = it.col();
        if (j == i) continue;
        const double f = it.value();
        s0 += f * B(j, 0);
        s1 += f * B(j, 1);
        s2 += f * B(j, 2);
        if (j < i && j >= first) {
          l0 += f * dB(j, 0);
          l1 += f * dB(j, 1);
          l2 += f * dB(j, 2);
        }
      }
      const double sum[3] = {s0, s1, s2}, lower[3] = {l0, l1, l2};
      for (int c = 0; c < 3; ++c) {
        const double updated = (p.E(i, c) + p.rho(i, c) * sum[c]) / D(i, c);
        dB(i, c) = updated - B(i, c);
        B(i, c) = updated;
        const double ri = std::abs(D(i, c) * dB(i, c) - p.rho(i, c) * lower[c]) / scale(c);
        finite = finite && std::isfinite(ri);
        r = std::max(r, ri);
      }
    }
    exchange_rows(B, blocks);
    return distributed::max_over_ranks(finite ? r : std::numeric_limits<double>::infinity());
  });
  s.seconds = timer.seconds();
  return s;
}

}  // namespace radwalk
