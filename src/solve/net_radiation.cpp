#include "solve/net_radiation.h"

#include <Eigen/Dense>
#include <cmath>
#include <string>

#include "core/check.h"
#include "core/error.h"
#include "core/format_number.h"

namespace radwalk {
namespace {

double sky_of(const NetRadiationInput& input, std::size_t i) { return input.sky.empty() ? 0.0 : input.sky[i]; }

}  // namespace

NetRadiationCoefficients net_radiation_coefficients(const NetRadiationInput& input) {
  const std::size_t n = input.area.size();
  RADWALK_CHECK_EQ(input.surface.size(), n);
  if (!input.sky.empty()) RADWALK_CHECK_EQ(input.sky.size(), n);
  const double Ta = input.ambient_temperature;
  if (!(Ta >= 0 && std::isfinite(Ta)))
    throw InputError("ambient temperature " + format_number(Ta) + " K: must be finite and >= 0");
  const double ambient = kStefanBoltzmann * Ta * Ta * Ta * Ta;  // sigma T_a^4, the ambient's radiosity
  NetRadiationCoefficients c;
  c.rho.resize(n);
  c.source.resize(n);
  bool anchored = false;  // some patch fixes the temperature level
  for (std::size_t i = 0; i < n; ++i) {
    const SurfaceCondition& s = input.surface[i];
    const std::string at = "patch " + std::to_string(i) + ": ";
    if (!(s.emissivity > 0 && s.emissivity <= 1))
      throw InputError(at + "emissivity " + format_number(s.emissivity) + " must be in (0, 1]");
    const double sky = sky_of(input, i);
    if (!(sky >= 0 && sky <= 1))
      throw InputError(at + "sky view factor " + format_number(sky) + " must be in [0, 1]");
    if (s.temperature_given) {
      if (!(s.temperature >= 0 && std::isfinite(s.temperature)))
        throw InputError(at + "temperature " + format_number(s.temperature) + " K must be finite and >= 0");
      const double T = s.temperature;
      c.rho[i] = 1 - s.emissivity;
      c.source[i] = s.emissivity * kStefanBoltzmann * T * T * T * T + c.rho[i] * sky * ambient;
      anchored = true;
    } else {
      if (!std::isfinite(s.heat_flux))
        throw InputError(at + "heat flux " + format_number(s.heat_flux) + " must be finite");
      c.rho[i] = 1;
      c.source[i] = s.heat_flux + sky * ambient;
      anchored = anchored || sky * input.area[i] > 0;
    }
  }
  if (n > 0 && !anchored)
    throw InputError("every surface has a given heat flux and nothing reaches an ambient: the temperatures are "
                     "determined only up to a constant (and the fluxes must sum to 0). Give at least one surface a "
                     "temperature (radwalk_temperature or --set NAME.temperature=T)");
  return c;
}

RadiosityProblem net_radiation_problem(const NetRadiationInput& input, SparseF F, RowBlocks row_blocks) {
  const NetRadiationCoefficients c = net_radiation_coefficients(input);
  const auto n = static_cast<Eigen::Index>(input.area.size());
  RADWALK_CHECK_EQ(F.rows(), n);
  RADWALK_CHECK_EQ(F.cols(), n);
  RadiosityProblem p;
  p.F = std::move(F);
  p.row_blocks = std::move(row_blocks);
  p.rho.resize(n, 3);
  p.E.resize(n, 3);
  p.area.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    p.rho.row(i) = Rgb::Constant(c.rho[k]).transpose();
    const double S = c.source[k];
    p.E(i, 0) = S > 0 ? S : 0.0;
    p.E(i, 1) = S < 0 ? -S : 0.0;
    p.E(i, 2) = p.E(i, 0);
    p.area(i) = input.area[k];
  }
  return p;
}

std::vector<double> radiosity_of(const Solution& solution) {
  std::vector<double> J(static_cast<std::size_t>(solution.B.rows()));
  for (Eigen::Index i = 0; i < solution.B.rows(); ++i)
    J[static_cast<std::size_t>(i)] = solution.B(i, 0) - solution.B(i, 1);
  return J;
}

NetRadiationResult net_radiation_result(const NetRadiationInput& input, const SparseF& F, std::vector<double> J) {
  const std::size_t n = input.area.size();
  RADWALK_CHECK_EQ(J.size(), n);
  RADWALK_CHECK_EQ(static_cast<std::size_t>(F.rows()), n);
  const double Ta = input.ambient_temperature;
  const double ambient = kStefanBoltzmann * Ta * Ta * Ta * Ta;
  NetRadiationResult r;
  r.G.assign(n, 0.0);
  r.q.assign(n, 0.0);
  r.Q.assign(n, 0.0);
  r.T.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    double gathered = 0;
    for (SparseF::InnerIterator it(F, static_cast<Eigen::Index>(i)); it; ++it)
      gathered += double(it.value()) * J[static_cast<std::size_t>(it.col())];
    r.G[i] = gathered + sky_of(input, i) * ambient;
    const SurfaceCondition& s = input.surface[i];
    if (s.temperature_given) {
      const double T = s.temperature;
      r.T[i] = T;
      r.q[i] = s.emissivity * (kStefanBoltzmann * T * T * T * T - r.G[i]);  // = J - G, without the cancellation
    } else {
      r.q[i] = s.heat_flux;
      const double emissive = r.G[i] + s.heat_flux / s.emissivity;  // sigma T^4
      if (!(emissive >= 0))
        throw InputError("patch " + std::to_string(i) +
                         ": the given heat flux q = " + format_number(s.heat_flux) +
                         " W/m^2 (net leaving) takes more than the surface absorbs (eps G = " +
                         format_number(s.emissivity * r.G[i]) + " W/m^2): no temperature gives it");
      r.T[i] = std::pow(emissive / kStefanBoltzmann, 0.25);
    }
    r.Q[i] = input.area[i] * r.q[i];
  }
  r.J = std::move(J);
  return r;
}

std::vector<double> dense_net_radiation(const NetRadiationInput& input, const SparseF& F) {
  const NetRadiationCoefficients c = net_radiation_coefficients(input);
  const auto n = static_cast<Eigen::Index>(input.area.size());
  Eigen::MatrixXd A = Eigen::MatrixXd::Identity(n, n);
  Eigen::VectorXd S(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (SparseF::InnerIterator it(F, i); it; ++it) A(i, it.col()) -= c.rho[std::size_t(i)] * double(it.value());
    S(i) = c.source[std::size_t(i)];
  }
  const Eigen::VectorXd J = A.partialPivLu().solve(S);
  return std::vector<double>(J.data(), J.data() + n);
}

}  // namespace radwalk
