#include "walk/measure_walks.h"

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/check.h"
#include "core/error.h"
#include "core/moments.h"
#include "core/parallel.h"
#include "core/timer.h"
#include "walk/importance_walk.h"
#include "walk/matrix_kernel.h"
#include "walk/random_walk_solver.h"
#include "walk/ray_kernel.h"
#include "walk/walk_estimators.h"
#include "walk/walk_lockstep.h"
#include "walk/walk_variance.h"

namespace radwalk {
namespace {

constexpr std::size_t kChunk = 4096;  // walks per chunk (a function of nothing but the walk index)

struct Part {
  Moments moments;
  WalkCounters counters;
};

Part merge_parts(Part acc, const Part& part) {
  acc.moments.merge(part.moments);
  acc.counters += part.counters;
  return acc;
}

// The per-walk scores of walks [begin, end) in walk order, added to a chunk's sums.
Moments moments_of(const std::vector<Rgb>& Z) {
  ShiftedSums sums;
  for (const Rgb& z : Z) sums.add(z);
  return sums.moments();
}

// Adjoint: walks from starts drawn in proportion to A_i R_i, scored (sum A R) X.
template <class Estimator, TransitionKernel K>
Part adjoint_walks(const K& kernel, const typename Estimator::Tables& tables, const AliasTable& start, double AR,
                   std::size_t begin, std::size_t end, std::uint64_t seed) {
  using Walk = typename Estimator::template Walk<K>;
  const RngFamily streams(seed, StreamDomain::measure_walk, 0);
  auto make = [&](std::size_t w) {
    Rng rng = streams.stream(begin + w);
    const std::size_t i = start.sample(rng.uniform());
    return Walk(kernel, tables, i, rng);
  };
  std::vector<Rgb> Z(end - begin, Rgb::Zero());
  Part part;
  run_lockstep(kernel, Z.size(), K::kLanes, make, [](Walk& walk, std::size_t, PatchIndex j) { walk.advance(j); },
               [&](std::size_t w, const Walk& walk) { Z[w] = AR * walk.score(); }, part.counters);
  part.moments = moments_of(Z);
  return part;
}

// Forward: particles scoring M_emitted + sum R_j power.
template <class Estimator, TransitionKernel K>
Part forward_particles(const K& kernel, const typename Estimator::Tables& tables, const ShootSource& source,
                       const Eigen::VectorXd& R, const Rgb& M_emitted, std::size_t begin, std::size_t end,
                       std::uint64_t seed) {
  using Particle = typename Estimator::template Particle<K>;
  const RngFamily streams(seed, StreamDomain::measure_walk, 0);
  auto make = [&](std::size_t w) { return Particle(kernel, tables, source, streams.stream(begin + w)); };
  std::vector<Rgb> Z(end - begin, M_emitted);
  Part part;
  run_lockstep(
      kernel, Z.size(), K::kLanes, make,
      [&](Particle& particle, std::size_t w, PatchIndex j) {
        particle.advance(j, [&](std::size_t jj, const Rgb& power) { Z[w] += R(Eigen::Index(jj)) * power; });
      },
      [](std::size_t, const Particle&) {}, part.counters);
  part.moments = moments_of(Z);
  return part;
}

// Per-walk exact variance of the adjoint estimator (matrix kernel).
Rgb adjoint_variance(const RadiosityProblem& problem, const WalkOptions& options, const Response& response,
                     const PatchRgb& B, const Rgb& M) {
  WalkOptions all = options;
  all.patches.clear();
  const PatchRgb var = theoretical_variance(problem, all, B);
  const Eigen::VectorXd w = problem.area.cwiseProduct(response.R);
  const double AR = w.sum();
  Rgb second = Rgb::Zero();
  for (Eigen::Index i = 0; i < w.size(); ++i)
    if (w(i) > 0) second += (w(i) / AR) * (var.row(i) + B.row(i).square()).transpose();
  return (AR * AR * second - M.square()).max(0.0);
}

// Per-particle exact variance of the forward estimator (matrix kernel; see measure_walks.h).
Rgb forward_variance(const RadiosityProblem& problem, const WalkOptions& options, const Response& response,
                     const std::vector<double>& p, const Rgb& M, const Rgb& M_emitted) {
  const Eigen::Index n = Eigen::Index(problem.size());
  const SparseF Ts = shooting_transfer(problem);
  const Eigen::MatrixXd T = Eigen::MatrixXd(Ts.cast<double>());
  const Eigen::VectorXd nk = T.rowwise().sum().cwiseMax(1.0);
  const ShootSource source = make_shoot_source(problem.E, problem.area);
  const Eigen::VectorXd& R = response.R;
  Rgb out;
  for (int c = 0; c < 3; ++c) {
    const Eigen::VectorXd rho = problem.rho.col(c).matrix();
    Eigen::VectorXd rho2_p(n);
    for (Eigen::Index j = 0; j < n; ++j) rho2_p(j) = rho(j) > 0 ? rho(j) * rho(j) / p[std::size_t(j)] : 0.0;
    const Eigen::MatrixXd TD = T * rho.asDiagonal();
    const Eigen::VectorXd u =
        (Eigen::MatrixXd::Identity(n, n) - TD).partialPivLu().solve(TD * R);
    Eigen::VectorXd a(n);
    for (Eigen::Index j = 0; j < n; ++j) {
      const double pj = p[std::size_t(j)];
      switch (options.method) {
        case WalkMethod::shoot_collision: a(j) = R(j) * R(j) + 2 * R(j) * u(j); break;
        case WalkMethod::shoot_absorption: a(j) = pj < 1 ? R(j) * R(j) / (1 - pj) : 0.0; break;
        case WalkMethod::shoot_survival: a(j) = pj > 0 ? (R(j) * R(j) + 2 * R(j) * u(j)) / pj : 0.0; break;
        default: RADWALK_CHECK(false);  // only shooting methods come here
      }
    }
    const Eigen::MatrixXd NT = nk.asDiagonal() * T;
    const Eigen::VectorXd rhs = NT * (rho.array().square() * a.array()).matrix();
    const Eigen::VectorXd v =
        (Eigen::MatrixXd::Identity(n, n) - NT * rho2_p.asDiagonal()).partialPivLu().solve(rhs);
    if (!v.allFinite() || v.minCoeff() < 0) {
      out(c) = std::numeric_limits<double>::infinity();
      continue;
    }
    double second = 0;
    for (Eigen::Index i = 0; i < n; ++i)
      if (source.power > 0 && source.W0[std::size_t(i)](c) > 0)
        second += source.birth.pdf(std::size_t(i)) * source.W0[std::size_t(i)](c) * source.W0[std::size_t(i)](c) * v(i);
    const double mean = M(c) - M_emitted(c);
    out(c) = std::max(0.0, second - mean * mean);
  }
  return out;
}

template <TransitionKernel K>
Part run_measure(const K& kernel, const RadiosityProblem& problem, const WalkOptions& options,
                 const Response& response, long walks) {
  const auto n = static_cast<std::size_t>(walks);
  return with_estimator_tables(options.method, kernel, [&](auto method, const auto& tables) {
    using Method = decltype(method);
    using Estimator = typename Method::Estimator;
    if constexpr (Method::kDirection == WalkDirection::gather) {
      std::vector<double> w(problem.size());
      for (std::size_t i = 0; i < w.size(); ++i)
        w[i] = problem.area(Eigen::Index(i)) * response.R(Eigen::Index(i));
      const AliasTable start(w);
      double AR = 0;
      for (double x : w) AR += x;
      return deterministic_reduce(
          n, kChunk, Part{},
          [&](std::size_t b, std::size_t e) { return adjoint_walks<Estimator>(kernel, tables, start, AR, b, e, options.seed); },
          merge_parts);
    } else {
      const ShootSource source = make_shoot_source(problem.E, problem.area);
      const Rgb M_emitted = measure(problem.area, response.R, problem.E);
      if (!(source.power > 0)) {  // nothing emitted: every particle would score M_emitted = 0
        Part part;
        for (std::size_t w = 0; w < n; ++w) part.moments.add(M_emitted);
        return part;
      }
      return deterministic_reduce(
          n, kChunk, Part{},
          [&](std::size_t b, std::size_t e) {
            return forward_particles<Estimator>(kernel, tables, source, response.R, M_emitted, b, e, options.seed);
          },
          merge_parts);
    }
  });
}

// Refuses a system whose Neumann series diverges (no finite B to measure), as solve_random_walk does.
void check_convergent(const RadiosityProblem& problem, const std::string& method) {
  const WalkConvergence convergence = check_walks_converge(problem, method);
  if (!convergence.refusal.empty()) throw NumericalError(convergence.refusal);
}

}  // namespace

MeasureEstimate measure_random_walk(const RadiosityProblem& problem, const PatchSet* patches,
                                    const Visibility* visibility, const WalkOptions& options,
                                    const Response& response, long walks, bool theory) {
  const std::size_t N = problem.size();
  check_response(response, N);
  WalkOptions checked = options;
  checked.walks_per_patch = checked.particles = walks;
  checked.patches.clear();
  check_walk_options(checked, N);
  const bool F_stored = problem.F.rows() == Eigen::Index(N) && problem.F.cols() == problem.F.rows();
  if (options.kernel == WalkKernel::matrix) RADWALK_CHECK(F_stored);
  if (options.kernel == WalkKernel::ray) {
    RADWALK_CHECK(patches != nullptr && visibility != nullptr);
    RADWALK_CHECK_EQ(patches->size(), N);
  }
  MeasureEstimate est;
  est.method = std::string(method_name(options.method));
  if (F_stored) check_convergent(problem, est.method);
  std::vector<double> p = survival_probabilities(problem.rho, options.survival);
  check_survival_probabilities(p, problem.rho, options.survival.rule);

  const Timer timer;
  Part part;
  if (options.kernel == WalkKernel::matrix) {
    const MatrixKernel kernel(problem, p, direction_of(options.method));
    part = run_measure(kernel, problem, options, response, walks);
  } else {
    const RayKernel kernel(problem, *patches, *visibility, p);
    part = run_measure(kernel, problem, options, response, walks);
  }
  est.seconds = timer.seconds();
  est.walks = walks;
  est.counters = part.counters;
  est.M = part.moments.mean;
  est.var = part.moments.variance();
  est.se = part.moments.standard_error();
  if (theory && options.kernel == WalkKernel::matrix && N <= kMaxTheoryPatches) {
    const PatchRgb B = dense_radiosity(problem);
    const Rgb M = measure(problem.area, response.R, B);
    est.var_theory = is_gathering(options.method)
                         ? adjoint_variance(problem, options, response, B, M)
                         : forward_variance(problem, options, response, p, M,
                                            measure(problem.area, response.R, problem.E));
  }
  return est;
}

MeasureEstimate measure_importance(const RadiosityProblem& problem, const Response& response,
                                   ImportanceDirection direction, const PatchRgb& importance, double alpha,
                                   long walks, std::uint64_t seed, bool theory) {
  const Eigen::Index n = Eigen::Index(problem.size());
  check_response(response, problem.size());
  if (walks < 2) throw InputError("importance walks: at least 2 walks are needed (got " + std::to_string(walks) + ")");
  RADWALK_CHECK_EQ(importance.rows(), n);
  MeasureEstimate est;
  est.method = direction == ImportanceDirection::from_sensor ? "importance-gather" : "importance-shoot";
  check_convergent(problem, est.method);
  const Timer timer;
  // The rows walked: F (from the sensor) or T = A^-1 F^T A (from the sources), in double (so that T diag(rho)
  // is exactly the operator of the adjoint system solve_adjoint_direct solves, up to double rounding).
  SparseD rows = problem.F.cast<double>();
  if (direction == ImportanceDirection::from_sources) {
    rows = SparseD(rows.transpose());
    for (Eigen::Index k = 0; k < rows.outerSize(); ++k)
      for (SparseD::InnerIterator it(rows, k); it; ++it) it.valueRef() *= problem.area(it.col()) / problem.area(k);
  }
  const Eigen::VectorXd AR = problem.area.cwiseProduct(response.R);
  for (int c = 0; c < 3; ++c) {
    const Eigen::VectorXd rho = problem.rho.col(c).matrix(), E = problem.E.col(c).matrix();
    const Eigen::VectorXd g = importance.col(c).matrix();
    // From the sensor: x = B_c, K = diag(rho_c) F, s = E_c, r = A.*R; from the sources: x = Y_c,
    // K = T diag(rho_c), s = R, r = A.*E_c (importance_walk.h).
    const bool sensor = direction == ImportanceDirection::from_sensor;
    const SparseD K = sensor ? SparseD(rho.asDiagonal() * rows) : SparseD(rows * rho.asDiagonal());
    const Eigen::VectorXd s = sensor ? E : response.R;
    const Eigen::VectorXd r = sensor ? AR : Eigen::VectorXd(problem.area.cwiseProduct(E));
    if (!(r.maxCoeff() > 0)) {  // nothing to measure in this channel (no emission, or no sensor): M_c = 0
      est.M(c) = est.se(c) = est.var(c) = 0;
      if (theory) est.var_theory(c) = 0;
      continue;
    }
    const ImportanceChain chain(K, s, r, g, alpha);
    const ChainEstimate ce = run_importance_walks(chain, walks, seed, c);
    est.M(c) = ce.mean;
    est.var(c) = ce.var;
    est.se(c) = ce.se;
    est.counters.steps += ce.steps;
    if (theory) est.var_theory(c) = chain.exact_variance();
  }
  est.walks = walks;
  est.seconds = timer.seconds();
  return est;
}

}  // namespace radwalk
