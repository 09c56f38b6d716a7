#include "solve/discretisation_error.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "core/check.h"
#include "core/moments.h"
#include "core/timer.h"
#include "solve/block_jacobi.h"
#include "solve/error_propagation.h"
#include "solve/form_factor_error.h"
#include "solve/fluctuation_source.h"

namespace radwalk {

namespace {

// The largest emission or radiosity, for moment_scale: the estimate is linear in (E, B) together.
double largest_value(const PatchSet& patches, const PatchRgb& B) {
  double largest = B.size() > 0 ? B.abs().maxCoeff() : 0.0;
  for (const Rgb& e : patches.E) largest = std::max(largest, e.abs().maxCoeff());
  return largest;
}

// A copy of the patches with E / s (only made when s != 1: emission near the largest double, whose squares in
// the estimate's variances would overflow).
PatchSet scaled_emission(const PatchSet& patches, double s) {
  PatchSet out = patches;
  for (Rgb& e : out.E) e /= s;
  return out;
}

}  // namespace

PriorClasses prior_classes(const std::vector<double>& area, const std::vector<bool>& counted) {
  PriorClasses out;
  out.of.assign(area.size(), 0);
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < area.size(); ++i)
    if (counted[i] && area[i] > 0) order.push_back(i);
  out.count = 1;
  if (order.empty()) return out;
  // Largest first, ties by index; level of i: floor(log4(A_max / A_i)).
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return area[a] > area[b]; });
  const double largest = area[order.front()];
  std::vector<long> level(order.size());
  for (std::size_t r = 0; r < order.size(); ++r)
    level[r] = static_cast<long>(std::floor(std::log(largest / area[order[r]]) / std::log(4.0)));
  // Walk the levels from the largest: a class closes at a level boundary once it holds kPriorClassPatches; a last
  // class below that joins the one before.
  std::vector<std::size_t> class_of_rank(order.size());
  std::size_t cls = 0, in_class = 0;
  for (std::size_t r = 0; r < order.size(); ++r) {
    if (r > 0 && in_class >= kPriorClassPatches && level[r] != level[r - 1]) {
      ++cls;
      in_class = 0;
    }
    class_of_rank[r] = cls;
    ++in_class;
  }
  if (cls > 0 && in_class < kPriorClassPatches)
    for (std::size_t r = order.size() - in_class; r < order.size(); ++r) class_of_rank[r] = cls - 1;
  out.count = class_of_rank.back() + 1;
  // The counted patches' classes; every other patch takes the class of the counted patch nearest to it in area.
  std::vector<double> ranked_area(order.size());
  for (std::size_t r = 0; r < order.size(); ++r) {
    out.of[order[r]] = class_of_rank[r];
    ranked_area[r] = area[order[r]];
  }
  for (std::size_t i = 0; i < area.size(); ++i) {
    if (counted[i] && area[i] > 0) continue;
    // ranked_area is descending: r the first rank whose area is <= area[i]; the nearer in log-area of r and r - 1.
    const auto it = std::lower_bound(ranked_area.begin(), ranked_area.end(), area[i], std::greater<double>());
    std::size_t r = std::min(static_cast<std::size_t>(it - ranked_area.begin()), order.size() - 1);
    if (r > 0 && area[i] > 0 &&
        std::abs(std::log(area[i] / ranked_area[r - 1])) < std::abs(std::log(area[i] / ranked_area[r])))
      --r;
    out.of[i] = class_of_rank[r];
  }
  return out;
}

DiscretisationError discretisation_error(const PatchSet& patches, const Visibility& visibility,
                                         const RadiosityProblem& p, const PatchRgb& B, int directions,
                                         std::uint64_t seed, ShooterAttribution* attribution) {
  // d and e are linear in (E, B) together: for values whose squares overflow, estimate for (E, B) / s and scale
  // the results back (moment_scale: s = 1 for ordinary values).
  const double scale = moment_scale(largest_value(patches, B));
  if (scale != 1.0) {
    DiscretisationError out =
        discretisation_error(scaled_emission(patches, scale), visibility, p, B / scale, directions, seed, attribution);
    out.estimate *= scale;
    out.standard_error *= scale;
    out.source *= scale;
    out.source_sd *= scale;
    if (attribution) {  // c_j is quadratic in (E, B)
      for (double& c : attribution->share) c *= scale * scale;
      attribution->total *= scale * scale;
    }
    return out;
  }
  Timer timer;
  const Eigen::Index N = static_cast<Eigen::Index>(patches.size());
  RADWALK_CHECK_EQ(B.rows(), N);
  RADWALK_CHECK_EQ(static_cast<Eigen::Index>(p.size()), N);
  FluctuationSource source = fluctuation_source(patches, visibility, B, directions, seed, 4, attribution != nullptr);
  DiscretisationError out;
  out.points = source.points;
  out.directions = source.directions;
  out.near_field_patches = source.near_field_patches;
  out.rays = source.rays;
  // H from the stored F, or from the estimate's own shot rays when the solver stored none.
  out.own_form_factors = p.F.nonZeros() == 0 && source.F.nonZeros() > 0;
  RadiosityProblem own;
  if (out.own_form_factors) {
    own.F = std::move(source.F);
    own.rho = p.rho;
    own.E = p.E;
    own.area = p.area;
  }
  const RadiosityProblem& h = out.own_form_factors ? own : p;
  const RowBlock rhs = source.d;
  out.source = source.d;
  out.source_sd = source.variance.sqrt();
  const BlockSolution e = solve_block_jacobi(h, rhs, 1e-6, "error estimate: the discretisation error's solve");
  // propagate_gather_variance propagates rho^2 V: V = Var(d) / rho^2 where rho > 0 (d is 0 elsewhere).
  const PatchRgb V = (p.rho > 0).select(source.variance / p.rho.square().max(1e-300), 0.0);
  const PropagatedVariance variance = propagate_gather_variance(h, V, 16, seed);
  out.sweeps = e.sweeps + variance.sweeps;
  if (attribution) {
    *attribution = ShooterAttribution{};
    if (h.row_blocks.empty()) {
      *attribution = shooter_attribution(patches, visibility, h, B, source, directions, seed);
      out.rays += attribution->rays;
    }
  }
  out.estimate = e.X;
  // Empirical Bayes (docs/theory/discretisation_error.md): e_i ~ N(0, t_c^2 B_ic^2) a priori, t_c^2 fitted over
  // the patches of i's size class (prior_classes; at least the scene's), e^ ~ N(e, V) given e; then with
  // w = tau^2 / (tau^2 + V):
  // B_disc^2 = (w e^)^2 + w V, whose mean over a class is its tau^2 (unbiased in aggregate, where e^2 + V would count
  // the noise twice). Scaled before squaring (core/moments.h), as the statistical part.
  const double s = moment_scale(N ? std::max(out.estimate.abs().maxCoeff(), B.abs().maxCoeff()) : 0.0);
  const PatchRgb e2 = (out.estimate / s).square(), Ve = variance.variance / (s * s), B2 = (B / s).square();
  std::vector<bool> counted(static_cast<std::size_t>(N));
  for (Eigen::Index i = 0; i < N; ++i)  // the reflecting, non-emitting patches (an emitter's B is mostly its exact E)
    counted[static_cast<std::size_t>(i)] = p.rho.row(i).maxCoeff() > 0 && !(p.E.row(i).maxCoeff() > 0);
  const PriorClasses classes = prior_classes(patches.area, counted);
  std::vector<Rgb> excess(classes.count, Rgb::Zero()), size(classes.count, Rgb::Zero());
  for (Eigen::Index i = 0; i < N; ++i) {
    if (!counted[static_cast<std::size_t>(i)]) continue;
    const std::size_t c = classes.of[static_cast<std::size_t>(i)];
    excess[c] += p.area[i] * (e2.row(i) - Ve.row(i)).transpose();
    size[c] += p.area[i] * B2.row(i).transpose();
  }
  Rgb all_excess = Rgb::Zero(), all_size = Rgb::Zero();
  for (std::size_t c = 0; c < classes.count; ++c) all_excess += excess[c], all_size += size[c];
  const Rgb t2_all = (all_size > 0).select((all_excess / all_size.max(1e-300)).max(0.0), 0.0);
  out.prior_relative = t2_all.sqrt();
  // A class's scale, but never below the scene's: a class whose estimates are mostly noise fits t near 0 and would
  // shrink them all to nothing.
  std::vector<Rgb> t2(classes.count);
  for (std::size_t c = 0; c < classes.count; ++c)
    t2[c] = (size[c] > 0).select((excess[c] / size[c].max(1e-300)).max(0.0), 0.0).max(t2_all);
  out.prior_classes = classes.count;
  out.standard_error.resize(N, 3);
  for (Eigen::Index i = 0; i < N; ++i)
    for (int c = 0; c < 3; ++c) {
      const double tau2 = t2[classes.of[static_cast<std::size_t>(i)]][c] * B2(i, c);
      const double w = tau2 + Ve(i, c) > 0 ? tau2 / (tau2 + Ve(i, c)) : 0.0;
      out.standard_error(i, c) = s * std::sqrt(std::max(w * w * e2(i, c) + w * Ve(i, c), e2(i, c) - Ve(i, c)));
    }
  out.seconds = timer.seconds();
  return out;
}

MeasurementDiscretisationError measurement_discretisation_error(const PatchSet& patches, const Visibility& visibility,
                                                                const RadiosityProblem& p, const PatchRgb& B,
                                                                const Eigen::VectorXd& W, int directions,
                                                                std::uint64_t seed) {
  const double scale = moment_scale(largest_value(patches, B));
  if (scale != 1.0) {
    MeasurementDiscretisationError out = measurement_discretisation_error(
        scaled_emission(patches, scale), visibility, p, B / scale, W, directions, seed);
    out.estimate *= scale;
    out.estimate_sd *= scale;
    out.share *= scale;
    out.standard_error *= scale;
    return out;
  }
  Timer timer;
  RADWALK_CHECK_EQ(B.rows(), static_cast<Eigen::Index>(patches.size()));
  const FluctuationSource source = fluctuation_source(patches, visibility, B, directions, seed);
  MeasurementDiscretisationError out = measurement_discretisation_error(p, source.d, source.variance.sqrt(), W);
  out.rays = source.rays;
  out.seconds = timer.seconds();
  return out;
}

MeasurementDiscretisationError measurement_discretisation_error(const RadiosityProblem& p, const PatchRgb& d_in,
                                                                const PatchRgb& d_sd, const Eigen::VectorXd& W) {
  Timer timer;
  RADWALK_CHECK_EQ(d_in.rows(), static_cast<Eigen::Index>(p.size()));
  // Scaled before squaring (core/moments.h): W near the largest double.
  const double r = moment_scale(W.size() > 0 ? W.cwiseAbs().maxCoeff() : 0.0);
  long sweeps = 0;
  const PatchRgb psi = adjoint_weights(p, W / r, sweeps);
  MeasurementDiscretisationError out = measurement_discretisation_error(psi, r, d_in, d_sd);
  out.sweeps = sweeps;
  out.seconds = timer.seconds();
  return out;
}

MeasurementDiscretisationError measurement_discretisation_error(const PatchRgb& psi, double r, const PatchRgb& d_in,
                                                                const PatchRgb& d_sd) {
  Timer timer;
  RADWALK_CHECK_EQ(d_in.rows(), psi.rows());
  RADWALK_CHECK_EQ(d_sd.rows(), d_in.rows());
  MeasurementDiscretisationError out;
  // Scaled before squaring (core/moments.h): d near the largest double.
  const double s = moment_scale(d_in.size() > 0 ? std::max(d_in.abs().maxCoeff(), d_sd.maxCoeff()) : 0.0);
  const PatchRgb d = d_in / s;
  const PatchRgb var = (d_sd / s).square();
  const Rgb eps = (psi * d).colwise().sum().transpose();
  const Rgb v = (psi.square() * var).colwise().sum().transpose();
  out.share = psi * d * (r * s);
  out.estimate = eps * (r * s);
  out.estimate_sd = v.sqrt() * (r * s);
  out.standard_error = (eps.square() + v).sqrt() * (r * s);
  out.seconds = timer.seconds();
  return out;
}

PatchRgb total_error(const PatchRgb& B_se, const PatchRgb& B_disc) {
  if (B_se.size() && B_disc.size()) return combined_standard_error(B_se, B_disc);
  return B_se.size() ? B_se : B_disc;
}

}  // namespace radwalk
