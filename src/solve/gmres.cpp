#include "solve/gmres.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/timer.h"
#include "solve/convergence.h"
#include "solve/iteration_progress.h"
#include "solve/residual.h"

namespace radwalk {
namespace {

using Vector = Eigen::VectorXd;

// One channel's operator A = I - diag(rho) F with its Gauss-Seidel splitting M = D - L, over the raw arrays of
// the compressed row-major F (columns sorted within a row; split[i] is the first entry of row i right of the
// diagonal).
class Splitting {
 public:
  Splitting(const SparseF& F, const Eigen::Ref<const Vector>& rho) : F_(F), rho_(rho) {
    const Eigen::Index n = F.rows();
    D_.resize(n);
    split_.resize(std::size_t(n));
    const auto* outer = F.outerIndexPtr();
    const auto* inner = F.innerIndexPtr();
    const auto* value = F.valuePtr();
    for (Eigen::Index i = 0; i < n; ++i) {
      double diagonal = 0;
      auto k = outer[i];
      while (k < outer[i + 1] && inner[k] < i) ++k;
      if (k < outer[i + 1] && inner[k] == i) diagonal = value[k++];
      split_[std::size_t(i)] = k;
      D_(i) = 1 - rho(i) * diagonal;
    }
  }

  // z = M^-1 v (forward substitution), then w = A z = v - U z.
  void apply_preconditioned(const Vector& v, Vector& z, Vector& w) const {
    forward(v, z);
    const auto* outer = F_.outerIndexPtr();
    const auto* inner = F_.innerIndexPtr();
    const auto* value = F_.valuePtr();
    const Eigen::Index n = F_.rows();
    for (Eigen::Index i = 0; i < n; ++i) {
      double upper = 0;
      for (auto k = split_[std::size_t(i)]; k < outer[i + 1]; ++k) upper += double(value[k]) * z(inner[k]);
      w(i) = v(i) - rho_(i) * upper;
    }
  }

  // z = M^-1 v: z_i = (v_i + rho_i sum_{j<i} F_ij z_j) / D_i.
  void forward(const Vector& v, Vector& z) const {
    const auto* outer = F_.outerIndexPtr();
    const auto* inner = F_.innerIndexPtr();
    const auto* value = F_.valuePtr();
    const Eigen::Index n = F_.rows();
    for (Eigen::Index i = 0; i < n; ++i) {
      double lower = 0;
      const auto end = split_[std::size_t(i)];
      for (auto k = outer[i]; k < end && inner[k] < i; ++k) lower += double(value[k]) * z(inner[k]);
      z(i) = (v(i) + rho_(i) * lower) / D_(i);
    }
  }

  // r = b - A x = b - x + rho .* (F x).
  void residual(const Vector& b, const Vector& x, Vector& r) const {
    const auto* outer = F_.outerIndexPtr();
    const auto* inner = F_.innerIndexPtr();
    const auto* value = F_.valuePtr();
    const Eigen::Index n = F_.rows();
    for (Eigen::Index i = 0; i < n; ++i) {
      double gathered = 0;
      for (auto k = outer[i]; k < outer[i + 1]; ++k) gathered += double(value[k]) * x(inner[k]);
      r(i) = b(i) - x(i) + rho_(i) * gathered;
    }
  }

  const Vector& diagonal() const { return D_; }

 private:
  const SparseF& F_;
  Vector rho_;
  Vector D_;
  std::vector<std::int32_t> split_;
};

// Outcome of one channel's solve.
struct ChannelResult {
  long iterations = 0;
  bool stagnated = false;
  bool broke_down = false;
};

// GMRES(m) on A M^-1 y = b for one channel, from x = b / D; stops when ||b - A x||_inf <= target (exact residual,
// checked after every cycle), at the budget, or when three cycles in a row fail to halve the residual (rounding).
ChannelResult gmres_channel(const Splitting& S, const Vector& b, double target, long budget, Vector& x,
                            std::vector<double>& history, double scale, IterationProgress& progress,
                            long done_before) {
  const Eigen::Index n = b.size();
  const int m = int(std::min<Eigen::Index>(kGmresRestart, std::max<Eigen::Index>(n, 1)));
  ChannelResult out;
  x = b.cwiseQuotient(S.diagonal());
  Vector r(n), z(n), w(n);
  S.residual(b, x, r);
  double best = r.lpNorm<Eigen::Infinity>();
  int slow_cycles = 0;
  std::vector<Vector> V(std::size_t(m + 1), Vector(n));
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(m + 1, m);
  Vector cs(m), sn(m), g(m + 1);
  while (true) {
    const double r_inf = r.lpNorm<Eigen::Infinity>();
    if (!(r_inf > target) || out.iterations >= budget) break;
    const double beta = r.norm();
    if (!std::isfinite(beta)) {
      out.broke_down = true;
      break;
    }
    V[0] = r / beta;
    g.setZero();
    g(0) = beta;
    H.setZero();
    int k = 0;
    for (; k < m && out.iterations < budget; ++k) {
      S.apply_preconditioned(V[std::size_t(k)], z, w);
      for (int j = 0; j <= k; ++j) {  // modified Gram-Schmidt
        H(j, k) = w.dot(V[std::size_t(j)]);
        w -= H(j, k) * V[std::size_t(j)];
      }
      H(k + 1, k) = w.norm();
      const bool lucky = !(H(k + 1, k) > 1e-300);
      if (!lucky) V[std::size_t(k + 1)] = w / H(k + 1, k);
      for (int j = 0; j < k; ++j) {  // the earlier rotations on the new column
        const double a = H(j, k), c = H(j + 1, k);
        H(j, k) = cs(j) * a + sn(j) * c;
        H(j + 1, k) = -sn(j) * a + cs(j) * c;
      }
      const double a = H(k, k), c = H(k + 1, k), h = std::hypot(a, c);
      cs(k) = h > 0 ? a / h : 1;
      sn(k) = h > 0 ? c / h : 0;
      H(k, k) = h;
      H(k + 1, k) = 0;
      g(k + 1) = -sn(k) * g(k);
      g(k) = cs(k) * g(k);
      ++out.iterations;
      const double estimate = std::abs(g(k + 1));
      history.push_back(estimate / scale);
      progress.update(done_before + out.iterations, estimate / scale);
      if (lucky || estimate <= target) {
        ++k;
        break;
      }
    }
    // x += M^-1 V y with H y = g (upper triangular k x k).
    Vector y = g.head(k);
    for (int i = k - 1; i >= 0; --i) {
      for (int j = i + 1; j < k; ++j) y(i) -= H(i, j) * y(j);
      y(i) = H(i, i) != 0 ? y(i) / H(i, i) : 0;
    }
    Vector update = Vector::Zero(n);
    for (int j = 0; j < k; ++j) update += y(j) * V[std::size_t(j)];
    S.forward(update, z);
    x += z;
    S.residual(b, x, r);
    const double now = r.lpNorm<Eigen::Infinity>();
    if (!std::isfinite(now)) {
      out.broke_down = true;
      break;
    }
    slow_cycles = now > 0.5 * best ? slow_cycles + 1 : 0;
    best = std::min(best, now);
    if (slow_cycles >= 3 && now > target) {
      out.stagnated = true;
      break;
    }
  }
  return out;
}

}  // namespace

Solution solve_gmres(const RadiosityProblem& p, const SolveOptions& options) {
  check_problem(p);
  check_options(options);
  Timer timer;
  Solution s;
  s.method = "gmres";
  const Eigen::Index n = Eigen::Index(p.size());
  const Rgb scale = residual_scale(p.E);
  PatchRgb B = PatchRgb::Zero(n, 3);
  std::vector<double> history;
  long iterations = 0;
  Verdict verdict = Verdict::keep_going;
  std::string why;
  IterationProgress progress("gmres iterations", options.tol, options.max_iterations);
  int solved = 0;
  for (int c = 0; c < 3 && verdict == Verdict::keep_going; ++c) {
    int same = -1;  // an earlier channel with the same rho and E
    for (int e = 0; e < c && same < 0; ++e)
      if ((p.rho.col(e) == p.rho.col(c)).all() && (p.E.col(e) == p.E.col(c)).all()) same = e;
    if (same >= 0) {
      B.col(c) = B.col(same);
      continue;
    }
    const Vector rho = p.rho.col(c).matrix();
    const Splitting S(p.F, rho);
    if (!(S.diagonal().array() > 0).all()) {
      verdict = Verdict::diverged;
      why = "gmres cannot split the system: a diagonal entry 1 - rho_i F_ii of channel " + std::to_string(c) +
            " is not positive (rho F_ii >= 1: the patch reflects all it sends onto itself)";
      break;
    }
    const Vector b = p.E.col(c).matrix();
    Vector x;
    const ChannelResult result = gmres_channel(S, b, options.tol * scale(c), options.max_iterations - iterations, x,
                                               history, scale(c), progress, iterations);
    iterations += result.iterations;
    ++solved;
    B.col(c) = x.array();
    if (result.broke_down) {
      verdict = Verdict::diverged;
      why = "gmres broke down on channel " + std::to_string(c) + " (the residual is not finite)";
    } else if (result.stagnated) {
      verdict = Verdict::stagnated;
      why = "gmres stagnated on channel " + std::to_string(c) + ": three restart cycles did not halve the residual "
            "(tol below the rounding level of the float F, or a singular system: every row re-radiating with "
            "nothing absorbing)";
    }
  }
  progress.finish();
  // E >= 0 and I - H a nonsingular M-matrix (radius of H below 1) give B = (I - H)^-1 E >= E >= 0; a clearly
  // negative B means the radius is not below 1 (a singular system that the float rounding of F made barely
  // invertible): no physical radiosity, whatever the residual.
  const double largest = B.abs().maxCoeff();
  if (verdict == Verdict::keep_going && B.allFinite() && B.minCoeff() < -1e-6 * largest) {
    verdict = Verdict::diverged;
    why = "gmres: the solution has negative radiosities (down to " + std::to_string(B.minCoeff()) +
          " against a largest |B| of " + std::to_string(largest) + "): I - diag(rho) F is singular or not an "
          "M-matrix (the spectral radius of diag(rho) F is >= 1), so no finite non-negative radiosity exists. In "
          "`exchange`: every surface re-radiating with nothing absorbing; give one a temperature.";
    finish_iterative(s, p, options, std::move(B), verdict, why, iterations, std::move(history), "iterations");
    s.status = SolveStatus::diverged;  // even where the residual met tol
    s.message = why;
    s.seconds = timer.seconds();
    return s;
  }
  s.info["restart"] = kGmresRestart;
  s.info["channels_solved"] = solved;
  finish_iterative(s, p, options, std::move(B), verdict, why, iterations, std::move(history), "iterations");
  s.seconds = timer.seconds();
  return s;
}

}  // namespace radwalk
