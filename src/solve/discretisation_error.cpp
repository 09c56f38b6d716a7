#include "solve/discretisation_error.h"

#include <algorithm>
#include <cmath>

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
  // Empirical Bayes (docs/theory/discretisation_error.md): e_i ~ N(0, t_c^2 B_ic^2) a priori, t_c^2 from all the
  // patches, e^ ~ N(e, V) given e; then E[e^2 | e^] = e^2 w^2 + tau^2 w V / tau^2 ... written with
  // w = tau^2 / (tau^2 + V): B_disc^2 = (w e^)^2 + w V, whose mean over the patches is tau^2 (unbiased in aggregate,
  // where e^2 + V would count the noise twice). Scaled before squaring (core/moments.h), as the statistical part.
  const double s = moment_scale(N ? std::max(out.estimate.abs().maxCoeff(), B.abs().maxCoeff()) : 0.0);
  const PatchRgb e2 = (out.estimate / s).square(), Ve = variance.variance / (s * s), B2 = (B / s).square();
  Rgb excess = Rgb::Zero(), size = Rgb::Zero();
  for (Eigen::Index i = 0; i < N; ++i) {
    // Over the reflecting, non-emitting patches (an emitter's B is mostly its own exact E).
    if (!(p.rho.row(i).maxCoeff() > 0) || p.E.row(i).maxCoeff() > 0) continue;
    excess += p.area[i] * (e2.row(i) - Ve.row(i)).transpose();
    size += p.area[i] * B2.row(i).transpose();
  }
  out.prior_relative = (size > 0).select((excess / size.max(1e-300)).max(0.0), 0.0).sqrt();
  out.standard_error.resize(N, 3);
  for (Eigen::Index i = 0; i < N; ++i)
    for (int c = 0; c < 3; ++c) {
      const double tau2 = out.prior_relative[c] * out.prior_relative[c] * B2(i, c);
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
