#include "solve/form_factor_error.h"

#include <algorithm>

#include "core/check.h"
#include "core/error.h"
#include "core/moments.h"
#include "formfactor/form_factor_noise.h"
#include "solve/iteration_progress.h"

namespace radwalk {

FormFactorError form_factor_error(const PatchSet& patches, const Visibility& visibility, const FormFactors& ff,
                                  const RadiosityProblem& p, const PatchRgb& B, int probes) {
  FormFactorError out;
  const double s = moment_scale(B.size() > 0 ? B.abs().maxCoeff() : 0.0);
  const PatchRgb b = B / s;
  out.calibration = calibrate_sampling_factors(patches, visibility, p.F, ff, b, p.row_blocks);
  const GatherVariance gathers = gather_variance(p.F, ff, b, p.row_blocks);
  out.propagation = propagate_gather_variance(p, gathers.scaled(out.calibration.factors), probes, ff.options.seed);
  out.standard_error = out.propagation.variance.sqrt() * s;
  SamplingFactors mean_variance = out.calibration.factors;  // a sum over many rows: kappa = 1
  mean_variance.coverage = 1;
  out.gather_standard_error = gathers.scaled(mean_variance).sqrt() * s;
  return out;
}

std::optional<FormFactorError> add_form_factor_error(const PatchSet& patches, const Visibility& visibility,
                                                     const FormFactors& ff, const RadiosityProblem& p,
                                                     Solution& solution) {
  const Eigen::Index N = static_cast<Eigen::Index>(patches.size());
  if (solution.B.rows() != N) return std::nullopt;
  const PatchRgb own = solution.B_se.rows() == N ? solution.B_se : PatchRgb::Zero(N, 3);
  if (!has_noise_model(ff)) {
    solution.B_se = own;
    return std::nullopt;
  }
  FormFactorError error = form_factor_error(patches, visibility, ff, p, solution.B);
  solution.B_se = combined_standard_error(own, error.standard_error);
  return error;
}

PatchRgb combined_standard_error(const PatchRgb& a, const PatchRgb& b) {
  const PatchRgb larger = a.max(b);
  return (larger > 0).select(larger * ((a.min(b) / larger).square() + 1.0).sqrt(), PatchRgb::Zero(a.rows(), 3));
}

PatchRgb adjoint_weights(const RadiosityProblem& p, const Eigen::VectorXd& W, long& sweeps) {
  const Eigen::Index N = static_cast<Eigen::Index>(p.size());
  RADWALK_CHECK_EQ(W.size(), N);
  RADWALK_CHECK(p.row_blocks.empty());
  // Psi = W + F^T (rho Psi), all channels at once; F^T applied by scattering F's rows.
  PatchRgb psi(N, 3), next(N, 3);
  for (int c = 0; c < 3; ++c) psi.col(c) = W.array();
  IterationProgress progress("error estimate: an adjoint's sweeps", 1e-10, 100000);
  for (;;) {
    for (int c = 0; c < 3; ++c) next.col(c) = W.array();
    for (Eigen::Index i = 0; i < N; ++i) {
      const auto source = (p.rho.row(i) * psi.row(i)).eval();
      for (SparseF::InnerIterator it(p.F, i); it; ++it) next.row(it.col()) += double(it.value()) * source;
    }
    ++sweeps;
    const double change = (next - psi).abs().maxCoeff(), size = next.abs().maxCoeff();
    progress.update(sweeps, size > 0 ? change / size : 0.0);
    psi.swap(next);
    if (!(change > 1e-10 * size)) break;
    if (sweeps >= 100000)
      throw InputError("error estimate: the adjoint of the measurement did not converge in 100,000 sweeps "
                       "(spectral radius of diag(rho) F near 1)");
  }
  return psi;
}

MeasurementError measurement_form_factor_error(const PatchSet& patches, const Visibility& visibility,
                                               const FormFactors& ff, const RadiosityProblem& p, const PatchRgb& B,
                                               const Eigen::VectorXd& W) {
  const Eigen::Index N = static_cast<Eigen::Index>(p.size());
  RADWALK_CHECK_EQ(W.size(), N);
  RADWALK_CHECK(p.row_blocks.empty());
  MeasurementError out;
  const double s = moment_scale(B.size() > 0 ? B.abs().maxCoeff() : 0.0);
  const double r = moment_scale(W.size() > 0 ? W.cwiseAbs().maxCoeff() : 0.0);
  const PatchRgb b = B / s;
  out.calibration = calibrate_sampling_factors(patches, visibility, p.F, ff, b);
  SamplingFactors mean_variance = out.calibration.factors;  // M sums many rows: their mean variance, kappa = 1
  mean_variance.coverage = 1;
  const PatchRgb V = gather_variance(p.F, ff, b).scaled(mean_variance);
  const PatchRgb psi = adjoint_weights(p, W / r, out.sweeps);
  out.standard_error = ((psi * p.rho).square() * V).colwise().sum().transpose().sqrt() * s * r;
  return out;
}

}  // namespace radwalk
