#include "walk/importance_walk.h"

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <string>

#include "core/check.h"
#include "core/error.h"
#include "core/parallel.h"
#include "walk/walk_variance.h"

namespace radwalk {
namespace {

void check_vector(const Eigen::VectorXd& v, const char* name, Eigen::Index n) {
  if (v.size() != n)
    throw InputError(std::string("importance walk: ") + name + " has " + std::to_string(v.size()) +
                     " entries for a system of " + std::to_string(n));
  for (Eigen::Index i = 0; i < n; ++i)
    if (!std::isfinite(v(i)) || v(i) < 0)
      throw InputError(std::string("importance walk: ") + name + "[" + std::to_string(i) + "] = " +
                       number_text(v(i)) + " is not a finite number >= 0");
}

// a / b, 0 where b = 0.
double ratio(double a, double b) { return b > 0 ? a / b : 0.0; }

}  // namespace

ImportanceChain::ImportanceChain(const SparseD& K, const Eigen::VectorXd& s, const Eigen::VectorXd& r,
                                 const Eigen::VectorXd& g, double alpha)
    : K_(K), s_(s), r_(r) {
  const Eigen::Index n = K.rows();
  if (K.cols() != n) throw InputError("importance walk: K is not square");
  check_vector(s, "s", n);
  check_vector(r, "r", n);
  check_vector(g, "g", n);
  if (!(alpha >= 0 && alpha <= 1))
    throw InputError("importance walk: the defensive fraction " + number_text(alpha) + " is not in [0, 1]");
  for (Eigen::Index k = 0; k < n; ++k)
    for (SparseD::InnerIterator it(K, k); it; ++it)
      if (!std::isfinite(it.value()) || it.value() < 0)
        throw InputError("importance walk: K(" + std::to_string(k) + ", " + std::to_string(it.col()) + ") = " +
                         number_text(it.value()) + " is not a finite number >= 0");

  // Start: pi_i = (1 - alpha) r_i g_i / <r, g> + alpha r_i / sum r.
  const double rg = r.dot(g), rsum = r.sum();
  std::vector<double> start(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i)
    start[std::size_t(i)] = (1 - alpha) * ratio(r(i) * g(i), rg) + alpha * ratio(r(i), rsum);
  start_ = AliasTable(start);  // InputError when no start has positive probability
  start_pdf_.resize(start.size());
  start_factor_.resize(start.size());
  for (std::size_t i = 0; i < start.size(); ++i) {
    start_pdf_[i] = start_.pdf(i);
    start_factor_[i] = ratio(r(Eigen::Index(i)), start_pdf_[i]);
  }

  // Outcomes of each state: the moves k -> j with P_kj > 0, then the stop with q_k > 0.
  begin_.assign(std::size_t(n) + 1, 0);
  std::vector<double> q;
  std::vector<std::int32_t> label;
  for (Eigen::Index k = 0; k < n; ++k) {
    double Kg = 0, row = 0;
    for (SparseD::InnerIterator it(K, k); it; ++it) {
      Kg += it.value() * g(it.col());
      row += it.value();
    }
    const double d = s(k) + Kg, nk = std::max(1.0, row);
    const std::size_t first = outcome_.size();
    for (SparseD::InnerIterator it(K, k); it; ++it) {
      const double P = (1 - alpha) * ratio(it.value() * g(it.col()), d) + alpha * it.value() / nk;
      if (P > 0) outcome_.push_back({static_cast<std::int32_t>(it.col()), it.value() / P}), outcome_pdf_.push_back(P);
    }
    const double stop = (1 - alpha) * ratio(s(k), d) + alpha * std::max(0.0, 1 - row / nk);
    if (stop > 0) outcome_.push_back({-1, s(k) / stop}), outcome_pdf_.push_back(stop);
    begin_[std::size_t(k) + 1] = outcome_.size();
    // Normalise against rounding (the probabilities sum to 1 up to a few ulps) and build the row's buckets.
    const std::size_t m = outcome_.size() - first;
    if (m == 0) continue;
    double total = 0;
    for (std::size_t o = first; o < outcome_.size(); ++o) total += outcome_pdf_[o];
    q.assign(m, 0);
    label.resize(m);
    for (std::size_t o = 0; o < m; ++o) {
      q[o] = outcome_pdf_[first + o] / total;
      label[o] = static_cast<std::int32_t>(first + o);
    }
    buckets_.resize(outcome_.size());
    build_alias_buckets(q.data(), label.data(), m, buckets_.data() + first);
  }
}

double ImportanceChain::walk(Rng& rng, long& steps) const {
  std::size_t k = start_.sample(rng.uniform());
  double Z = start_factor_[k];
  for (long step = 0; step < kMaxSteps; ++step) {
    const std::size_t b = begin_[k], m = begin_[k + 1] - b;
    if (m == 0) return 0.0;  // no outcome: x_k = 0 here
    const Outcome& o = outcome_[std::size_t(sample_alias_buckets(buckets_.data() + b, m, rng.uniform()))];
    ++steps;
    Z *= o.factor;
    if (o.state < 0) return Z;
    k = static_cast<std::size_t>(o.state);
  }
  throw NumericalError("importance walk: a walk took " + std::to_string(kMaxSteps) +
                       " steps without stopping (the chain does not end: use a defensive fraction > 0)");
}

double ImportanceChain::exact_variance() const {
  const Eigen::Index n = K_.rows();
  if (static_cast<std::size_t>(n) > kMaxTheoryPatches)
    throw InputError("importance walk: exact variance needs N <= " + std::to_string(kMaxTheoryPatches) +
                     " (N = " + std::to_string(n) + ")");
  // x = (I - K)^-1 s, M = <r, x>.
  Eigen::MatrixXd IK = Eigen::MatrixXd::Identity(n, n), IK2 = Eigen::MatrixXd::Identity(n, n);
  Eigen::VectorXd c = Eigen::VectorXd::Zero(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    for (SparseD::InnerIterator it(K_, k); it; ++it) IK(k, it.col()) -= it.value();
    // K2_kj = K_kj^2 / P_kj = K_kj * factor; c_k = s_k^2 / q_k = s_k * factor of the stop.
    for (std::size_t o = begin_[std::size_t(k)]; o < begin_[std::size_t(k) + 1]; ++o) {
      const Outcome& out = outcome_[o];
      if (out.state < 0)
        c(k) = s_(k) * out.factor;
      else
        IK2(k, out.state) -= out.factor * out.factor * outcome_pdf_[o];
    }
  }
  const Eigen::VectorXd x = IK.partialPivLu().solve(s_);
  const double M = r_.dot(x);
  const Eigen::VectorXd V = IK2.partialPivLu().solve(c);
  if (!V.allFinite() || V.minCoeff() < 0) return std::numeric_limits<double>::infinity();
  double second = 0;
  for (Eigen::Index i = 0; i < n; ++i)
    if (start_pdf_[std::size_t(i)] > 0) second += r_(i) * r_(i) * V(i) / start_pdf_[std::size_t(i)];
  return std::max(0.0, second - M * M);
}

ChainEstimate run_importance_walks(const ImportanceChain& chain, long walks, std::uint64_t seed, int channel) {
  RADWALK_CHECK_GE(walks, 2);
  constexpr long kChunk = 4096;
  const RngFamily streams(seed, StreamDomain::importance_walk, static_cast<std::uint64_t>(channel));
  const auto n = static_cast<std::size_t>(walks);
  struct Part {
    Moments moments;
    long steps = 0;
  };
  const Part all = deterministic_reduce(
      n, kChunk, Part{},
      [&](std::size_t b, std::size_t e) {
        ShiftedSums sums;
        Part part;
        for (std::size_t w = b; w < e; ++w) {
          Rng rng = streams.stream(w);
          sums.add(Rgb::Constant(chain.walk(rng, part.steps)));
        }
        part.moments = sums.moments();
        return part;
      },
      [](Part acc, const Part& part) {
        acc.moments.merge(part.moments);
        acc.steps += part.steps;
        return acc;
      });
  const Moments& m = all.moments;
  ChainEstimate est;
  est.walks = walks;
  est.steps = all.steps;
  est.mean = m.mean(0);
  est.var = m.variance()(0);
  est.se = m.standard_error()(0);
  return est;
}

}  // namespace radwalk
