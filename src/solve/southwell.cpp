#include "solve/southwell.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/check.h"
#include "core/error.h"
#include "core/timer.h"
#include "solve/convergence.h"
#include "solve/iteration_progress.h"
#include "solve/residual.h"

namespace radwalk {
namespace {

// Complete binary tree over the patches: each node holds the largest shooting priority below it (and whose it
// is) and the largest |dB_c| per channel below it.
class TournamentTree {
 public:
  explicit TournamentTree(Eigen::Index n) {
    while (leaves_ < n) leaves_ *= 2;
    nodes_.assign(std::size_t(2 * leaves_), Node{});
  }
  void set(Eigen::Index i, double priority, const double (&abs_dB)[3]) {
    std::size_t k = std::size_t(leaves_ + i);
    nodes_[k] = Node{priority, std::int32_t(i), {abs_dB[0], abs_dB[1], abs_dB[2]}};
    for (k /= 2; k >= 1; k /= 2) {
      const Node& a = nodes_[2 * k];
      const Node& b = nodes_[2 * k + 1];
      Node& m = nodes_[k];
      m.priority = a.priority >= b.priority ? a.priority : b.priority;
      m.index = a.priority >= b.priority ? a.index : b.index;
      for (int c = 0; c < 3; ++c) m.abs_dB[c] = std::max(a.abs_dB[c], b.abs_dB[c]);
    }
  }
  Eigen::Index top() const { return nodes_[1].index; }
  double top_priority() const { return nodes_[1].priority; }
  double max_abs(int c) const { return nodes_[1].abs_dB[c]; }

 private:
  struct Node {
    double priority = -1;
    std::int32_t index = -1;
    double abs_dB[3] = {0, 0, 0};
  };
  Eigen::Index leaves_ = 1;
  std::vector<Node> nodes_;
};

// ambient_c = sum_j A_j dB_jc / sum_j A_j / (1 - rho_avg,c), dB = E - (I - H) B.
Rgb ambient_level(const RadiosityProblem& p, const PatchRgb& B) {
  const Eigen::Index n = Eigen::Index(p.size());
  RADWALK_CHECK_EQ(B.rows(), n);
  Rgb level = Rgb::Zero();
  if (n == 0) return level;
  const PatchRgb dB = residual(p, B);
  const double total_area = p.area.sum();
  for (int c = 0; c < 3; ++c) {
    const double rho_avg = p.area.dot(p.rho.col(c).matrix()) / total_area;
    if (!(rho_avg < 1))
      throw NumericalError("southwell_ambient: area-weighted mean reflectance " + std::to_string(rho_avg) +
                       " of channel " + std::to_string(c) +
                       " is >= 1, so the interreflection factor 1 / (1 - rho_avg) does not exist");
    level(c) = p.area.dot(dB.col(c).matrix()) / total_area / (1 - rho_avg);
  }
  return level;
}

}  // namespace

Solution solve_southwell(const RadiosityProblem& p, const SolveOptions& options) {
  check_problem(p);
  check_options(options);
  if (options.iterate_every < 0)
    throw InputError("southwell: iterate_every " + std::to_string(options.iterate_every) + " must be >= 0");
  Timer timer;
  Solution s;
  s.method = "southwell";
  const Eigen::Index n = Eigen::Index(p.size());
  // Optimistic: one shot per sweep at the Gauss-Seidel rate (convergence.h); the watch below is sharper.
  const StabilityCheck check = check_stability(p, options, s.method, 0.5);
  record_stability(check, s);
  PatchRgb B = PatchRgb::Zero(n, 3);
  if (!check.ok || n == 0) {
    finish_iterative(s, p, options, std::move(B), refusal(check), check.message, 0, {}, "shots");
    s.seconds = timer.seconds();
    return s;
  }

  const PatchRgb D = system_diagonal(p);
  const Rgb scale = residual_scale(p.E);
  const SparseF Ft = p.F.transpose();  // row i of F^T = column i of F
  s.info["transpose_bytes"] = double(Ft.nonZeros()) * (sizeof(float) + sizeof(std::int32_t));

  PatchRgb dB = p.E;
  TournamentTree tree(n);
  const auto refresh = [&](Eigen::Index j) {
    const double a[3] = {std::abs(dB(j, 0)), std::abs(dB(j, 1)), std::abs(dB(j, 2))};
    tree.set(j, p.area(j) * (a[0] + a[1] + a[2]), a);
  };
  const auto relative = [&] {
    double worst = 0;
    for (int c = 0; c < 3; ++c) worst = std::max(worst, tree.max_abs(c) / scale(c));
    return worst;
  };
  for (Eigen::Index j = 0; j < n; ++j) refresh(j);

  const long every = options.iterate_every > 0 ? options.iterate_every : long(n);
  long reported = 0;  // shot count of the last on_iterate call
  std::vector<double> history{relative()};
  std::string why;
  Verdict verdict = Verdict::keep_going;
  long shots = 0;
  IterationProgress progress("southwell shots", options.tol, options.max_iterations);
  progress.update(0, history.back());
  for (int restart = 0; restart < 3; ++restart) {
    while (shots < options.max_iterations && relative() > options.tol) {
      // Shoot the patch with the most unshot power.
      const Eigen::Index i = tree.top();
      double shot[3];
      for (int c = 0; c < 3; ++c) {
        shot[c] = dB(i, c) / D(i, c);
        B(i, c) += shot[c];
        dB(i, c) = 0;
      }
      for (SparseF::InnerIterator it(Ft, i); it; ++it) {
        const auto j = it.col();
        if (j == i) continue;
        const double f = it.value();
        for (int c = 0; c < 3; ++c) dB(j, c) += p.rho(j, c) * f * shot[c];
        refresh(j);
      }
      refresh(i);
      ++shots;
      if (options.on_iterate && shots % every == 0) {
        options.on_iterate(shots, B);
        reported = shots;
      }
      if (shots % n == 0) {
        history.push_back(relative());
        progress.update(shots, history.back());
        verdict = judge_progress(history, long(n), options, s.method, &why);
        if (verdict != Verdict::keep_going) break;
      }
    }
    if (verdict != Verdict::keep_going && verdict != Verdict::converged) break;
    if (relative() > options.tol) break;  // out of budget
    // The tracked dB met tol; make sure rounding drift did not fool it.
    dB = residual(p, B);
    for (Eigen::Index j = 0; j < n; ++j) refresh(j);
    if (relative() <= options.tol) {
      verdict = Verdict::converged;
      break;
    }
  }
  history.push_back(relative());
  progress.finish();
  if (options.on_iterate && shots > reported) options.on_iterate(shots, B);
  finish_iterative(s, p, options, std::move(B), verdict, why, shots, std::move(history), "shots");
  if (s.B.allFinite()) {
    try {
      const Rgb level = ambient_level(p, s.B);
      for (int c = 0; c < 3; ++c) s.info[std::string("ambient_") + "rgb"[c]] = level(c);
    } catch (const NumericalError&) {  // rho_avg >= 1: no ambient term exists
    }
  }
  s.seconds = timer.seconds();
  return s;
}

PatchRgb southwell_ambient(const RadiosityProblem& p, const PatchRgb& B) {
  check_problem(p);
  const Rgb level = ambient_level(p, B);
  PatchRgb ambient = p.rho;
  for (int c = 0; c < 3; ++c) ambient.col(c) *= level(c);
  return ambient;
}

}  // namespace radwalk
