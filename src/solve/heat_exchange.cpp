#include "solve/heat_exchange.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "core/error.h"
#include "core/format_number.h"
#include "formfactor/form_factor_noise.h"
#include "patch/patch_grouping.h"
#include "solve/form_factor_error.h"
#include "solve/solve_radiosity.h"
#include "visibility/embree_visibility.h"

namespace radwalk {
namespace {

double sum_of_squares(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x * x;
  return s;
}

// Step 4: the statistical errors of J, q, Q, T from the traced F's noise.
// `own`: the solver's own standard error of J per patch (random walks; empty for a deterministic solver), added to
// the form factors' noise (when F was traced) as an independent error.
void statistical_errors(const PatchSet& patches, const FormFactors& ff, const std::vector<double>& own,
                        HeatExchange& x) {
  const std::size_t n = patches.size();
  const NetRadiationResult& r = x.result;
  PatchRgb V = PatchRgb::Zero(Eigen::Index(n), 3);
  if (has_noise_model(ff)) {
    PatchRgb B3(Eigen::Index(n), 3);
    for (std::size_t i = 0; i < n; ++i) B3.row(Eigen::Index(i)) = Rgb::Constant(r.J[i]).transpose();
    const EmbreeVisibility visibility(patches);
    const FormFactorError error = form_factor_error(patches, visibility, ff, x.problem, B3);
    V = gather_variance(x.problem.F, ff, B3).scaled(error.calibration.factors);
    for (std::size_t i = 0; i < n; ++i) x.J_se[i] = error.standard_error(Eigen::Index(i), 0);
  }
  for (std::size_t i = 0; i < own.size(); ++i) x.J_se[i] = std::hypot(x.J_se[i], own[i]);
  for (std::size_t i = 0; i < n; ++i) {
    const SurfaceCondition& s = x.input.surface[i];
    if (s.temperature_given) {
      if (s.emissivity < 1) {
        x.q_se[i] = s.emissivity / (1 - s.emissivity) * x.J_se[i];
      } else {
        double through = 0;
        for (SparseF::InnerIterator it(x.problem.F, Eigen::Index(i)); it; ++it)
          through += double(it.value()) * x.J_se[std::size_t(it.col())];
        x.q_se[i] = std::sqrt(V(Eigen::Index(i), 0) + through * through);
      }
    } else if (r.T[i] > 0) {
      x.T_se[i] = x.J_se[i] / (4 * kStefanBoltzmann * r.T[i] * r.T[i] * r.T[i]);
    }
    x.Q_se[i] = patches.area[i] * x.q_se[i];
  }
}

// Step 6: the energy balance.
HeatBalance energy_balance(const PatchSet& patches, const FormFactors& ff, const HeatExchange& x) {
  const std::size_t n = patches.size();
  const NetRadiationResult& r = x.result;
  const double ambient = kStefanBoltzmann * std::pow(x.input.ambient_temperature, 4);
  HeatBalance b;
  double var_backs = 0, var_to_ambient = 0, var_residual = 0;
  for (std::size_t i = 0; i < n; ++i) {
    // A closed cavity exchanges nothing with the rest (its J is 0 inside the solve, s = b = 0, no row of F): only
    // its given Q would enter, which no radiation carries anywhere.
    if (x.cavity[i] >= 0) continue;
    const double A = patches.area[i], s = x.input.sky[i];
    b.sum_Q += r.Q[i];
    b.to_ambient += A * r.J[i] * s;
    b.from_ambient += A * s * ambient;
    b.into_backs += A * r.J[i] * x.back[i];
    b.sky_area += A * s;
    if (x.traced) {
      const double rays = std::max<double>(ff.rays[i], 1);
      const double P = A * r.J[i];
      var_backs += P * P * x.back[i] * (1 - x.back[i]) / rays;
      var_to_ambient += P * P * s * (1 - s) / rays;
      double m1 = 0, m2 = 0;
      for (SparseF::InnerIterator it(x.problem.F, Eigen::Index(i)); it; ++it) {
        const double d = r.J[i] - r.J[std::size_t(it.col())];
        m1 += double(it.value()) * d;
        m2 += double(it.value()) * d * d;
      }
      var_residual += A * A * std::max(0.0, m2 - m1 * m1) / rays;
    }
  }
  b.residual = b.sum_Q - (b.to_ambient - b.from_ambient) - b.into_backs;
  b.sum_Q_se = std::sqrt(sum_of_squares(x.Q_se));  // 0 in the cavities
  b.to_ambient_se = std::sqrt(var_to_ambient);
  b.into_backs_se = std::sqrt(var_backs);
  b.residual_se = std::sqrt(var_residual);
  return b;
}

// Step 7: the per-group tables.
HeatExchangeGroups group_tables(const PatchSet& patches, const HeatExchange& x, const std::string& by) {
  const std::size_t n = patches.size();
  HeatExchangeGroups g;
  PatchGrouping grouping = group_patches(patches, by);
  g.names = std::move(grouping.names);
  g.group = std::move(grouping.group);
  const int groups = int(g.names.size());
  g.view_factors = group_view_factors(x.problem.F, patches.area, g.group, groups, x.input.sky, x.back);
  g.Q.assign(std::size_t(groups), 0.0);
  g.Q_se.assign(std::size_t(groups), 0.0);
  g.T_radiant.assign(std::size_t(groups), 0.0);
  std::vector<double>& radiating_area = g.radiating_area;
  radiating_area.assign(std::size_t(groups), 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto G = std::size_t(g.group[i]);
    g.Q[G] += x.result.Q[i];
    g.Q_se[G] += x.Q_se[i] * x.Q_se[i];
    // Only a patch that radiates counts: not one touching another surface (a contact patch, such as a cabinet's
    // bottom on the floor, whose rays leave through the floor's back to the ambient), nor one hidden inside a
    // closed object (every ray into a back): they have no irradiation, and a re-radiating one a T of 0 that is no
    // temperature of the group; nor one of a closed cavity, which radiation gives no temperature (step 2b).
    double seen = i < x.input.sky.size() ? x.input.sky[i] : 0.0;  // s_i + sum_j F_ij
    for (SparseF::InnerIterator it(x.problem.F, Eigen::Index(i)); it; ++it) seen += double(it.value());
    if ((i < x.in_contact.size() && x.in_contact[i]) || x.cavity[i] >= 0 || !(seen > 0)) continue;
    g.T_radiant[G] += patches.area[i] * std::pow(x.result.T[i], 4);
    radiating_area[G] += patches.area[i];
  }
  for (std::size_t G = 0; G < std::size_t(groups); ++G) {
    g.Q_se[G] = std::sqrt(g.Q_se[G]);
    g.T_radiant[G] = radiating_area[G] > 0 ? std::pow(g.T_radiant[G] / radiating_area[G], 0.25)
                                           : std::numeric_limits<double>::quiet_NaN();  // no value
  }
  return g;
}

// Distinct values of name(i) over `patches` (in their order), "(none)" for an empty one.
template <class Name>
std::vector<std::string> distinct_names(const std::vector<std::size_t>& members, Name name) {
  std::vector<std::string> out;
  for (std::size_t i : members) {
    std::string s = name(i);
    if (s.empty()) s = "(none)";
    if (std::find(out.begin(), out.end(), s) == out.end()) out.push_back(std::move(s));
  }
  return out;
}

// "'a', 'b', 'c' and 4 more" (at most `shown` names quoted).
std::string quoted_list(const std::vector<std::string>& names, std::size_t shown = 4) {
  std::string out;
  for (std::size_t k = 0; k < names.size() && k < shown; ++k) out += (k ? ", '" : "'") + names[k] + "'";
  if (names.size() > shown) out += " and " + std::to_string(names.size() - shown) + " more";
  return out;
}

// Removes the patches flagged in `out` from the system as step 2 and 2b do: their rows and columns of F dropped,
// what the others sent them counted with the backs (b_i += F_ij); they become black at 0 K with no sky and no
// back (rho = 0, S = 0: J = 0 in the solve).
void remove_from_system(const std::vector<bool>& out, FormFactors& ff, HeatExchange& x) {
  const std::size_t n = out.size();
  std::vector<Eigen::Triplet<float, std::int32_t>> kept;
  for (std::size_t i = 0; i < n; ++i) {
    if (out[i]) continue;
    for (SparseF::InnerIterator it(ff.F, Eigen::Index(i)); it; ++it) {
      if (out[std::size_t(it.col())])
        x.back[i] += double(it.value());
      else
        kept.emplace_back(std::int32_t(i), std::int32_t(it.col()), it.value());
    }
  }
  SparseF reduced(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  reduced.setFromTriplets(kept.begin(), kept.end());
  ff.F = std::move(reduced);
  for (std::size_t i = 0; i < n; ++i)
    if (out[i]) {
      x.input.sky[i] = x.back[i] = 0;
      x.input.surface[i] = SurfaceCondition{1.0, true, 0.0, 0.0};  // rho = 0, S = 0: J = 0
    }
}

}  // namespace

std::string cavity_warning(const HeatExchangeCavity& c) {
  const ClosedCavity& k = c.cavity;
  std::string text =
      "closed cavity: " + std::to_string(k.patches.size()) + " patches (" + format_number(k.area, 4) + " m^2) of object" +
      (c.objects.size() > 1 ? "s " : " ") + quoted_list(c.objects) + ", group" +
      (c.groups.size() > 1 ? "s " : " ") + quoted_list(c.groups) + ", all with a given heat flux, exchange " +
      (k.leak > 0 ? "only " + format_number(k.leak, 2) + " of their radiation" : "no radiation") +
      " with the rest of the scene (leak fraction below " +
      format_number(kCavityLeak, 0, NumberNotation::scientific) +
      "), so radiation leaves their temperature undetermined (in reality conduction sets it)";
  if (k.given_Q != 0)
    text += "; their given heat fluxes sum to " + format_number(k.given_Q, 4) +
            " W, which radiation cannot carry out";
  return text + ": their J, G and T are left empty (field cavity = 1) and out of the groups' T_radiant and the "
                "energy balance";
}

std::vector<double> undetermined_as_missing(std::vector<double> v, const HeatExchange& x) {
  for (std::size_t i = 0; i < v.size() && i < x.cavity.size(); ++i)
    if (x.cavity[i] >= 0) v[i] = std::numeric_limits<double>::quiet_NaN();
  return v;
}

HeatExchange exchange_heat(const PatchSet& patches, const std::vector<SurfaceCondition>& conditions,
                           const std::vector<ContactRegion>& regions, FormFactors ff,
                           const HeatExchangeOptions& options) {
  const std::size_t n = patches.size();
  if (conditions.size() != n)
    throw InputError("exchange: " + std::to_string(conditions.size()) + " surface conditions for " +
                     std::to_string(n) + " patches");
  if (options.group_by != "object" && options.group_by != "group" && options.group_by != "material")
    throw InputError("group_by '" + options.group_by + "' is not one of object, group, material");
  HeatExchange x;
  x.given = conditions;
  x.traced = ff.rays.size() == n;

  // Step 1.
  x.input.area = patches.area;
  x.input.surface = conditions;
  x.input.ambient_temperature = options.ambient_temperature;
  x.input.sky.assign(n, 0.0);
  x.back.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    if (x.traced) {
      const double rays = std::max<double>(ff.rays[i], 1);
      x.input.sky[i] = ff.escaped[i] / rays;
      x.back[i] = ff.back_hits[i] / rays;
    } else {
      const double row = double(ff.F.row(Eigen::Index(i)).sum());
      x.input.sky[i] = std::clamp(1.0 - row, 0.0, 1.0);
    }
  }

  // Step 2.
  x.in_contact = contact_patches(regions, patches);
  for (std::size_t i = 0; i < n; ++i)
    if (x.in_contact[i]) ++x.contact_count, x.contact_area += patches.area[i];
  if (options.exclude_contacts && x.contact_count > 0) remove_from_system(x.in_contact, ff, x);

  // Step 2b. The conditions are checked first (a scene where every surface has a given flux and nothing reaches an
  // ambient is refused as a whole, net_radiation_coefficients).
  net_radiation_coefficients(x.input);
  x.cavity.assign(n, -1);
  {
    std::vector<bool> in_cavity(n, false);
    for (ClosedCavity& c : closed_cavities(ff.F, x.input)) {
      HeatExchangeCavity k;
      k.objects = distinct_names(c.patches, [&](std::size_t i) { return patches.object_of(i); });
      k.groups = distinct_names(c.patches, [&](std::size_t i) { return patches.group_of(i); });
      k.materials = distinct_names(c.patches, [&](std::size_t i) { return patches.material_of(i); });
      for (std::size_t i : c.patches) x.cavity[i] = std::int32_t(x.cavities.size()), in_cavity[i] = true;
      k.cavity = std::move(c);
      x.cavities.push_back(std::move(k));
    }
    if (!x.cavities.empty()) {
      std::size_t determined = 0;
      for (std::size_t i = 0; i < n; ++i) determined += !in_cavity[i] && !(options.exclude_contacts && x.in_contact[i]);
      if (determined == 0)
        throw InputError("every surface lies in a closed cavity (" + cavity_warning(x.cavities.front()) +
                         "): give at least one surface a temperature (radwalk_temperature or --set NAME.temperature=T)");
      remove_from_system(in_cavity, ff, x);
    }
  }

  // Step 3. The error estimates below read the patches' rho and E: those of the net-radiation system (its rho
  // and source S), not the materials' reflectance and emission.
  x.coefficients = net_radiation_coefficients(x.input);
  PatchSet thermal = patches;
  for (std::size_t i = 0; i < n; ++i) {
    thermal.rho[i] = Rgb::Constant(x.coefficients.rho[i]);
    thermal.E[i] = Rgb::Constant(x.coefficients.source[i]);
  }
  x.problem = net_radiation_problem(x.input, std::move(ff.F));
  x.solution = options.solver ? options.solver(x.problem) : solve_radiosity(x.problem, options.solve);
  x.solved = x.solution.B.rows() == Eigen::Index(n);
  if (!x.solved) return x;
  x.result = net_radiation_result(x.input, x.problem.F, radiosity_of(x.solution));
  for (std::size_t i = 0; i < n; ++i)  // a cavity's net flux is the given one (its J, G, T: no value)
    if (x.cavity[i] >= 0) x.result.q[i] = conditions[i].heat_flux, x.result.Q[i] = patches.area[i] * x.result.q[i];

  // Step 4.
  x.J_se.assign(n, 0.0);
  x.q_se.assign(n, 0.0);
  x.Q_se.assign(n, 0.0);
  x.T_se.assign(n, 0.0);
  // A Monte Carlo solver's own error of J = B_0 - B_1: sqrt(se_0^2 + se_1^2), the channels taken as independent
  // (the walks carry both signed parts of the source, so their covariance, of either sign, is left out).
  std::vector<double> own;
  if (options.solver && x.solution.B_se.rows() == Eigen::Index(n))
    for (std::size_t i = 0; i < n; ++i)
      own.push_back(std::hypot(x.solution.B_se(Eigen::Index(i), 0), x.solution.B_se(Eigen::Index(i), 1)));
  const std::string walks_part = own.empty() ? "" : ", plus the solver's own (random walks') standard error";
  if (has_noise_model(ff)) {
    statistical_errors(thermal, ff, own, x);
    x.error_method =
        "first-order propagation of the traced rows' gather variance (docs/theory/error_estimate.md), sampling "
        "factors measured" + walks_part + "; q, Q and T linearly from J (docs/theory/net_radiation.md)";
  } else {
    x.error_note = ff.row_std_error.empty() ? "the noise of form factors read from a file is not included"
                                            : "the analytic form factors' visibility noise is not propagated";
    if (!own.empty()) statistical_errors(thermal, ff, own, x);
    x.error_method =
        (own.empty() ? std::string() : "the solver's own (random walks') standard error; ") + "not included: " +
        x.error_note;
  }

  // Step 5.
  if (options.discretisation_directions > 0)
    x.discretisation = exchange_discretisation(thermal, x.problem, x.solution.B, x.input, x.result,
                                               options.discretisation_directions, options.seed);

  for (std::size_t i = 0; i < n && !x.discretisation.q.empty(); ++i)
    if (x.cavity[i] >= 0) x.discretisation.q[i] = x.discretisation.Q[i] = 0;  // given

  // Step 6.
  x.balance = energy_balance(patches, ff, x);
  for (std::size_t i = 0; i < n; ++i)
    if (x.in_contact[i]) x.contact_radiated += patches.area[i] * x.result.J[i], x.contact_Q += x.result.Q[i];

  // Step 7.
  x.groups = group_tables(patches, x, options.group_by);
  return x;
}

}  // namespace radwalk
