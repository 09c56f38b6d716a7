// radwalk exchange SCENE: grey diffuse radiative heat exchange by the net-radiation method (solve/net_radiation.h,
// docs/heat-exchange.md, docs/theory/net_radiation.md): emissivity and temperature (or net heat flux) per material
// in, radiosity J, net flux q, net heat Q and temperature T per patch out, with their statistical errors, the
// energy balance in W and per-group tables.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "apps/options.h"
#include "apps/exchange_discretisation.h"
#include "apps/exchange_sensitivities.h"
#include "apps/pipeline.h"
#include "apps/run_metadata.h"
#include "core/error.h"
#include "core/parallel.h"
#include "formfactor/form_factor_noise.h"
#include "io/csv_writer.h"
#include "mesh/length_unit.h"
#include "patch/contact.h"
#include "solve/form_factor_error.h"
#include "solve/group_view_factors.h"
#include "solve/net_radiation.h"
#include "solve/solve_radiosity.h"
#include "visibility/embree_visibility.h"

namespace radwalk::app {
namespace {

std::string fmt(double x, const char* format = "%.6g") {
  char text[48];
  std::snprintf(text, sizeof text, format, x);
  return text;
}

// "file:line: material 'm'" or "material 'm'" when it comes from no file.
std::string material_where(const Material& m) {
  return (m.file.empty() ? std::string() : m.file + ":" + std::to_string(m.line) + ": ") + "material '" + m.name + "'";
}

// The thermal condition of every patch from its material (Material::emissivity, temperature, heat_flux). Every
// material some patch uses must give an emissivity and exactly one of temperature and heat flux: otherwise one
// InputError naming the first such material (file, line) and the MTL statement or --set that fixes it, and the
// count of the others.
std::vector<SurfaceCondition> surface_conditions(const PatchSet& patches) {
  std::vector<bool> used(patches.materials.size(), false);
  for (std::int32_t m : patches.material)
    if (m >= 0) used[std::size_t(m)] = true;
  std::vector<std::string> problems;
  for (std::size_t k = 0; k < patches.materials.size(); ++k) {
    if (!used[k]) continue;
    const Material& m = patches.materials[k];
    if (!m.emissivity)
      problems.push_back(material_where(m) + " has no emissivity: add 'radwalk_emissivity E' (0 < E <= 1) to its "
                         "block or --set '" + m.name + ".emissivity=E'");
    if (!m.temperature && !m.heat_flux)
      problems.push_back(material_where(m) + " has neither a temperature nor a heat flux: add 'radwalk_temperature "
                         "T' (kelvin) or 'radwalk_heat_flux q' (W/m^2, net leaving; 0 for a re-radiating wall), or "
                         "--set '" + m.name + ".temperature=T'");
    if (m.temperature && m.heat_flux)
      problems.push_back(material_where(m) + " has both radwalk_temperature and radwalk_heat_flux: a surface has one "
                         "known and one solved; remove one (or --set one, which drops the other)");
  }
  if (!problems.empty())
    throw InputError(problems.front() + (problems.size() > 1 ? " (and " + std::to_string(problems.size() - 1) +
                                                                     " more such problem(s) in other materials)"
                                                               : std::string()));
  std::vector<SurfaceCondition> s(patches.size());
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const Material& m = patches.materials[std::size_t(patches.material[i])];
    s[i].emissivity = *m.emissivity;
    s[i].temperature_given = m.temperature.has_value();
    s[i].temperature = m.temperature.value_or(0.0);
    s[i].heat_flux = m.heat_flux.value_or(0.0);
  }
  return s;
}

// The name of patch i's group under --group-by.
std::string group_name(const PatchSet& patches, std::size_t i, const std::string& by) {
  const std::string& name = by == "object" ? patches.object_of(i) : by == "group" ? patches.group_of(i)
                                                                                  : patches.material_of(i);
  return name.empty() ? "(none)" : name;
}

// The patches in contact with another surface (patch/contact.h): the faces lying back to back on a support (a
// furniture bottom on the floor) and the patches of the support faces whose centroid lies under a footprint (the
// floor under it, a patch of its own with --contact-cut). Both radiate only into the backs of faces (the floor
// under a bottom, the bottom's own inside): in reality they exchange heat by conduction, not radiation.
std::vector<bool> contact_patches(const Mesh& mesh, const PatchSet& patches) {
  std::vector<bool> in_contact(patches.size(), false);
  const std::vector<Contact> contacts = find_contacts(mesh);
  const double tol = kContactTolerance * std::max(patches.scene_extent(), 1e-300);
  for (const Contact& c : contacts) {
    const std::size_t m = c.footprint.size();
    if (m < 3) continue;
    // The support's normal: the footprint runs counter-clockwise about it (Newell).
    Vec3 n = Vec3::Zero();
    for (std::size_t k = 0; k < m; ++k) n += c.footprint[k].cross(c.footprint[(k + 1) % m]);
    if (!(n.norm() > 0)) continue;
    n.normalize();
    std::vector<long> lying, supports;
    if (c.lying)
      for (std::int32_t f : c.standing) lying.push_back(mesh.source_face(std::size_t(f)));
    for (std::int32_t f : c.supports) supports.push_back(mesh.source_face(std::size_t(f)));
    for (std::size_t i = 0; i < patches.size(); ++i) {
      const long face = patches.face[i];
      if (std::find(lying.begin(), lying.end(), face) != lying.end()) {
        in_contact[i] = true;
        continue;
      }
      // A patch in the support's plane whose centroid is inside the footprint: a face lying back to back on the
      // support (normal opposite: a bottom) or the support's own part under it (normal along, a support face).
      const Vec3& x = patches.centroid[i];
      if (std::abs((x - c.footprint[0]).dot(n)) > tol) continue;
      const double along = patches.normal[i].dot(n);
      const bool bottom = along < -0.999;
      const bool under = along > 0.999 && std::find(supports.begin(), supports.end(), face) != supports.end();
      if (!bottom && !under) continue;
      bool inside = true;
      for (std::size_t k = 0; k < m && inside; ++k)
        inside = (c.footprint[(k + 1) % m] - c.footprint[k]).cross(x - c.footprint[k]).dot(n) > tol * tol;
      if (inside) in_contact[i] = true;
    }
  }
  return in_contact;
}

SolveOptions solve_options(const ExchangeCommand& c, std::size_t patches) {
  SolveOptions o;
  o.solver = c.solver;
  o.auto_iterative = "gmres";  // re-radiating rows (rho = 1): docs/theory/net_radiation.md, "The Krylov solver"
  o.tol = c.tol;
  o.max_iterations = c.max_iterations > 0 ? c.max_iterations : default_max_iterations(c.solver, patches);
  return o;
}

double sum_of_squares(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x * x;
  return s;
}

}  // namespace

int run_exchange(const ExchangeCommand& command) {
  RunSummary summary("exchange", command.scene.argv);
  // sigma T^4 is in W/m^2, so areas must be in m^2: a named unit other than metres is refused (with the --scale that
  // converts it), an unnamed one is taken as metres.
  const std::string unit = length_unit(command.scene).length();
  if (unit != "m" && !command.scene.unit.empty())
    throw InputError("radwalk exchange works in metres (sigma T^4 is W/m^2) but the lengths are in " + unit +
                     ": use --unit " + command.scene.unit + " --scale " + fmt(metres_per(command.scene.unit)) +
                     " (lengths times the scale become metres)");
  Mesh mesh;
  PatchSet patches = load_patches(command.scene, summary, mesh);
  const std::vector<SurfaceCondition> conditions = surface_conditions(patches);
  for (const Material& m : patches.materials)
    if (m.Ke.maxCoeff() > 0)
      warn(summary, material_where(m) + " has an emitted radiance Ke: radwalk exchange ignores it (a surface emits "
                    "eps sigma T^4 from its radwalk_temperature)");
  ThreadLimit limit(command.scene.threads);
  const std::size_t n = patches.size();
  if (command.scene.unit.empty())
    note("lengths taken as metres (name the file's unit with --unit, and --scale to metres, if they are not)");

  // Form factors (every row on every process: the flux and balance stages read whole rows).
  FormFactors ff = obtain_form_factors(command.scene, command.ff, patches, summary, RowsHeld::every_row);
  std::vector<CellField> fields = form_factor_fields(ff, patches);
  const bool traced = ff.rays.size() == n;

  // Where the rays not caught by F go: with traced rays the escaped fraction reaches the ambient and the back hits
  // the backs of one-sided faces; with analytic or read F only 1 - row sum is known, all of it taken as sky.
  NetRadiationInput input;
  input.area = patches.area;
  input.surface = conditions;
  input.ambient_temperature = command.ambient_temperature;
  input.sky.assign(n, 0.0);
  std::vector<double> back(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    if (traced) {
      const double rays = std::max<double>(ff.rays[i], 1);
      input.sky[i] = ff.escaped[i] / rays;
      back[i] = ff.back_hits[i] / rays;
    } else {
      const double row = double(ff.F.row(Eigen::Index(i)).sum());
      input.sky[i] = std::clamp(1.0 - row, 0.0, 1.0);
    }
  }
  // Patches in contact with other surfaces: reported, and with --contact-faces exclude left out of the exchange
  // (their rows and columns of F removed, what other patches sent to them counted with the backs; J = q = Q = 0).
  const std::vector<bool> in_contact = contact_patches(mesh, patches);
  const bool exclude = command.contact_faces == "exclude";
  std::size_t contact_count = 0;
  double contact_area = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (in_contact[i]) ++contact_count, contact_area += patches.area[i];
  if (exclude && contact_count > 0) {
    std::vector<Eigen::Triplet<float, std::int32_t>> kept;
    for (std::size_t i = 0; i < n; ++i) {
      if (in_contact[i]) continue;
      for (SparseF::InnerIterator it(ff.F, Eigen::Index(i)); it; ++it) {
        if (in_contact[std::size_t(it.col())])
          back[i] += double(it.value());
        else
          kept.emplace_back(std::int32_t(i), std::int32_t(it.col()), it.value());
      }
    }
    SparseF reduced(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
    reduced.setFromTriplets(kept.begin(), kept.end());
    ff.F = std::move(reduced);
    for (std::size_t i = 0; i < n; ++i)
      if (in_contact[i]) {
        input.sky[i] = back[i] = 0;
        input.surface[i] = SurfaceCondition{1.0, true, 0.0, 0.0};  // rho = 0, S = 0: J = 0
      }
  }
  double sky_area = 0;
  for (std::size_t i = 0; i < n; ++i) sky_area += patches.area[i] * input.sky[i];
  if (!traced && sky_area > 1e-6 * patches.total_area())
    note("form factors not traced here (analytic or read from a file): 1 - the row sum of F is taken as the sky "
         "view factor; backs of one-sided faces cannot be told from the sky");
  if (sky_area > 1e-6 * patches.total_area() && command.ambient_temperature == 0 && !command.ambient_given)
    warn(summary, "part of the scene sees out (sky view factor x area = " + fmt(sky_area) +
                      " m^2): escaping radiation reaches an ambient at 0 K; give --ambient-temperature T");

  // The net-radiation system in radiosity form, solved by the chosen solver.
  const RadiosityProblem problem = net_radiation_problem(input, std::move(ff.F));
  // Patch description columns: the system's rho and source (E) of every patch.
  {
    const NetRadiationCoefficients c = net_radiation_coefficients(input);
    for (std::size_t i = 0; i < n; ++i) {
      patches.rho[i] = Rgb::Constant(c.rho[i]);
      patches.E[i] = Rgb::Constant(c.source[i]);
    }
  }
  Solution solution = solve_radiosity(problem, solve_options(command, n));
  summary.add_timing("solve", solution.seconds);
  std::fprintf(report_stream(), "%s: %s (%s)", solution.method.c_str(), to_string(solution.status),
               solution.message.c_str());
  if (solution.iterations > 0) std::fprintf(report_stream(), ", %ld iterations", solution.iterations);
  if (solution.residual == solution.residual)
    std::fprintf(report_stream(), ", relative residual %.3g", solution.residual);
  std::fprintf(report_stream(), ", %.3f s\n", solution.seconds);
  summary.json()["solution"] = solution_json(solution);
  if (solution.B.rows() != Eigen::Index(n)) {
    if (!command.scene.json.empty()) summary.write(command.scene.json);
    std::fprintf(stderr, "radwalk: %s did not converge: %s\n", solution.method.c_str(), solution.message.c_str());
    return solution.status == SolveStatus::max_iterations ? 1 : 3;
  }
  const NetRadiationResult r = net_radiation_result(input, problem.F, radiosity_of(solution));

  // Statistical errors from the traced F's noise (apps/statistical_error.h's machinery, first order): J_se by the
  // propagation of each row's gather variance through (I - diag(rho) F)^-1; then linearly
  //   known T, eps < 1: q = eps/(1 - eps) (sigma T^4 - J)      -> se(q) = eps/(1 - eps) se(J)
  //   known T, eps = 1: q = sigma T^4 - G                      -> se(q) = sqrt(V_G + (F se(J))^2) (a bound)
  //   known q:          sigma T^4 = J + q (1 - eps)/eps         -> se(T) = se(J) / (4 sigma T^3)
  std::vector<double> J_se(n, 0.0), q_se(n, 0.0), Q_se(n, 0.0), T_se(n, 0.0);
  std::string error_note;
  if (has_noise_model(ff)) {
    PatchRgb B3(Eigen::Index(n), 3);
    for (std::size_t i = 0; i < n; ++i) B3.row(Eigen::Index(i)) = Rgb::Constant(r.J[i]).transpose();
    const EmbreeVisibility visibility(patches);
    const FormFactorError error = form_factor_error(patches, visibility, ff, problem, B3);
    const PatchRgb V = gather_variance(problem.F, ff, B3).scaled(error.calibration.factors);
    for (std::size_t i = 0; i < n; ++i) J_se[i] = error.standard_error(Eigen::Index(i), 0);
    for (std::size_t i = 0; i < n; ++i) {
      const SurfaceCondition& s = input.surface[i];
      if (s.temperature_given) {
        if (s.emissivity < 1) {
          q_se[i] = s.emissivity / (1 - s.emissivity) * J_se[i];
        } else {
          double through = 0;
          for (SparseF::InnerIterator it(problem.F, Eigen::Index(i)); it; ++it)
            through += double(it.value()) * J_se[std::size_t(it.col())];
          q_se[i] = std::sqrt(V(Eigen::Index(i), 0) + through * through);
        }
      } else if (r.T[i] > 0) {
        T_se[i] = J_se[i] / (4 * kStefanBoltzmann * r.T[i] * r.T[i] * r.T[i]);
      }
      Q_se[i] = patches.area[i] * q_se[i];
    }
    summary.json()["exchange"]["error_method"] =
        "first-order propagation of the traced rows' gather variance (docs/theory/error_estimate.md), sampling "
        "factors measured; q, Q and T linearly from J (docs/theory/net_radiation.md)";
  } else {
    error_note = ff.row_std_error.empty() ? "the noise of form factors read from a file is not included"
                                          : "the analytic form factors' visibility noise is not propagated";
    summary.json()["exchange"]["error_method"] = "not included: " + error_note;
  }

  // The discretisation error of J, q, Q, T and the totals sqrt(se^2 + disc^2) (apps/exchange_discretisation.h).
  ExchangeDiscretisation disc;
  if (command.discretisation_directions > 0) {
    disc = exchange_discretisation(patches, problem, solution.B, input, r, command.discretisation_directions,
                                   command.scene.seed, summary);
    summary.add_timing("discretisation_error", disc.seconds);
    double J_disc_max = 0, J_rel = 0, J_power = 0, Q_disc_sum = 0;
    for (std::size_t i = 0; i < n; ++i) {
      J_disc_max = std::max(J_disc_max, disc.J[i]);
      J_rel += patches.area[i] * disc.J[i] * disc.J[i];
      J_power += patches.area[i] * r.J[i] * r.J[i];
      Q_disc_sum += disc.Q[i];
    }
    const double relative = J_power > 0 ? std::sqrt(J_rel / J_power) : 0.0;
    auto& jd = summary.json()["exchange"]["discretisation"];
    jd["J_disc_max"] = J_disc_max;
    jd["J_disc_relative"] = relative;
    jd["Q_disc_sum"] = Q_disc_sum;
    std::fprintf(report_stream(),
                 "discretisation error (1 sd equivalent): J_disc up to %.3g W/m^2, %.3g %% of J (area-weighted RMS); "
                 "sum of |Q_disc| %.3g W; per patch J_disc, q_disc, Q_disc, T_disc and the totals J_err, q_err, "
                 "Q_err, T_err = sqrt(se^2 + disc^2)\n",
                 J_disc_max, 100 * relative, Q_disc_sum);
  }

  // The energy balance, W: sum_i Q_i = (to the ambient) - (from the ambient) + (into the backs of one-sided faces)
  // + R, R = sum_i A_i sum_j F_ij (J_i - J_j) - sum_i A_i J_i (1 - r_i - s_i - b_i): the reciprocity defect of F,
  // zero for a reciprocal F. Its standard error from each row's rays (J held fixed, first order):
  //   Var(R) = sum_i A_i^2 (sum_j F_ij (J_i - J_j)^2 - (sum_j F_ij (J_i - J_j))^2) / n_i.
  const double ambient = kStefanBoltzmann * std::pow(command.ambient_temperature, 4);
  double total = 0, to_ambient = 0, from_ambient = 0, into_backs = 0, var_backs = 0, var_to_ambient = 0,
         var_residual = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double A = patches.area[i];
    total += r.Q[i];
    to_ambient += A * r.J[i] * input.sky[i];
    from_ambient += A * input.sky[i] * ambient;
    into_backs += A * r.J[i] * back[i];
    if (traced) {
      const double rays = std::max<double>(ff.rays[i], 1);
      const double P = A * r.J[i];
      var_backs += P * P * back[i] * (1 - back[i]) / rays;
      var_to_ambient += P * P * input.sky[i] * (1 - input.sky[i]) / rays;
      double m1 = 0, m2 = 0;
      for (SparseF::InnerIterator it(problem.F, Eigen::Index(i)); it; ++it) {
        const double d = r.J[i] - r.J[std::size_t(it.col())];
        m1 += double(it.value()) * d;
        m2 += double(it.value()) * d * d;
      }
      var_residual += A * A * std::max(0.0, m2 - m1 * m1) / rays;
    }
  }
  const double residual = total - (to_ambient - from_ambient) - into_backs;
  const double total_se = std::sqrt(sum_of_squares(Q_se));
  auto& jx = summary.json()["exchange"];
  jx["stefan_boltzmann"] = kStefanBoltzmann;
  jx["ambient_temperature"] = command.ambient_temperature;
  jx["length_unit"] = length_unit(command.scene).length();
  jx["sum_Q"] = total;
  jx["sum_Q_se"] = total_se;
  jx["to_ambient"] = to_ambient;
  jx["to_ambient_se"] = std::sqrt(var_to_ambient);
  jx["from_ambient"] = from_ambient;
  jx["lost_to_back_faces"] = into_backs;
  jx["lost_to_back_faces_se"] = std::sqrt(var_backs);
  jx["balance_residual"] = residual;
  jx["balance_residual_se"] = std::sqrt(var_residual);
  jx["sky_area"] = sky_area;
  if (traced && error_note.empty()) {
    std::fprintf(report_stream(),
                 "energy balance: sum of Q = %.6g W (+- %.2g); to the ambient %.6g W (+- %.2g), from it %.6g W; lost "
                 "into the backs of one-sided faces %.6g W (+- %.2g); residual %.3g W (+- %.2g, the form factors' "
                 "reciprocity defect)\n",
                 total, total_se, to_ambient, std::sqrt(var_to_ambient), from_ambient, into_backs,
                 std::sqrt(var_backs), residual, std::sqrt(var_residual));
  } else {
    // F not traced here: no statistical error (exact F: the residual is its rounding; a read F: unknown).
    std::fprintf(report_stream(),
                 "energy balance: sum of Q = %.6g W; to the ambient %.6g W, from it %.6g W; residual %.3g W (the form "
                 "factors' reciprocity defect and rows' rounding; F not traced here, so no error bars)\n",
                 total, to_ambient, from_ambient, residual);
  }
  if (!error_note.empty()) std::fprintf(report_stream(), "errors: %s\n", error_note.c_str());
  double largest = 0;
  for (double Q : r.Q) largest += std::abs(Q);
  if (into_backs > 0.01 * std::max(largest, 1e-300))
    warn(summary, fmt(into_backs) + " W (+- " + fmt(std::sqrt(var_backs), "%.2g") +
                      ") is radiated into the backs of one-sided faces, where it is lost (absorbed at 0 K): faces "
                      "oriented the wrong way (--orient outward), or open and thin parts that should be two-sided "
                      "(--open-shells two-sided, 'radwalk_two_sided 1', --two-sided); the back_hits field says where");

  // The contact patches' share, W.
  {
    double radiated = 0, net = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (in_contact[i]) radiated += patches.area[i] * r.J[i], net += r.Q[i];
    jx["contact_patches"] = contact_count;
    jx["contact_area"] = contact_area;
    jx["contact_faces"] = command.contact_faces;
    jx["contact_radiated"] = radiated;
    jx["contact_Q"] = net;
    if (contact_count > 0 && !exclude)
      warn(summary, std::to_string(contact_count) + " patches (" + fmt(contact_area) + " m^2) touch another surface "
                    "(faces lying on a support, e.g. furniture bottoms on the floor, and the support under them): "
                    "they radiate " + fmt(radiated) + " W into the backs of faces or out through the support, and their net heat is " + fmt(net) +
                    " W, which in reality is conduction through the contact; --contact-faces exclude leaves them out "
                    "of the exchange");
    else if (contact_count > 0)
      note(std::to_string(contact_count) + " contact patches (" + fmt(contact_area) + " m^2) left out of the exchange");
  }

  // Per-group tables.
  std::map<std::string, std::int32_t> index;
  std::vector<std::string> names;
  std::vector<std::int32_t> group(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::string name = group_name(patches, i, command.group_by);
    auto [it, fresh] = index.emplace(name, std::int32_t(names.size()));
    if (fresh) names.push_back(name);
    group[i] = it->second;
  }
  const int groups = int(names.size());
  const GroupViewFactors gv = group_view_factors(problem.F, patches.area, group, groups, input.sky, back);
  std::vector<double> group_Q(std::size_t(groups), 0.0), group_Q_var(std::size_t(groups), 0.0),
      group_T4(std::size_t(groups), 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto G = std::size_t(group[i]);
    group_Q[G] += r.Q[i];
    group_Q_var[G] += Q_se[i] * Q_se[i];
    group_T4[G] += patches.area[i] * std::pow(r.T[i], 4);
  }
  nlohmann::json table = nlohmann::json::array();
  for (int G = 0; G < groups; ++G) {
    const auto g = std::size_t(G);
    table.push_back({{"name", names[g]},
                     {"area", gv.area[g]},
                     {"Q", group_Q[g]},
                     {"Q_se", std::sqrt(group_Q_var[g])},
                     {"T_radiant", std::pow(group_T4[g] / gv.area[g], 0.25)},
                     {"sky", gv.sky[g]},
                     {"back", gv.back[g]}});
  }
  jx["group_by"] = command.group_by;
  jx["groups"] = table;
  jx["group_reciprocity_defect"] = group_reciprocity_defect(gv);
  if (!command.groups_csv.empty()) {
    std::vector<std::vector<std::string>> rows;
    for (int G = 0; G < groups; ++G) {
      const auto g = std::size_t(G);
      rows.push_back({csv_text(names[g]), csv_number(gv.area[g]), csv_number(group_Q[g]),
                      csv_number(std::sqrt(group_Q_var[g])), csv_number(std::pow(group_T4[g] / gv.area[g], 0.25)),
                      csv_number(gv.sky[g]), csv_number(gv.back[g])});
    }
    write_csv_table(command.groups_csv, {command.group_by, "area", "Q", "Q_se", "T_radiant", "sky", "back"}, rows,
                    run_id_of(summary));
    note("wrote " + command.groups_csv);
  }
  if (!command.group_factors.empty()) {
    std::vector<std::vector<std::string>> rows;
    for (int G = 0; G < groups; ++G) {
      for (int H = 0; H < groups; ++H)
        rows.push_back({csv_text(names[std::size_t(G)]), csv_text(names[std::size_t(H)]), csv_number(gv.F(G, H)),
                        csv_number(gv.area[std::size_t(G)] * gv.F(G, H))});
      rows.push_back({csv_text(names[std::size_t(G)]), "(ambient)", csv_number(gv.sky[std::size_t(G)]),
                      csv_number(gv.area[std::size_t(G)] * gv.sky[std::size_t(G)])});
      if (traced)
        rows.push_back({csv_text(names[std::size_t(G)]), "(back faces)", csv_number(gv.back[std::size_t(G)]),
                        csv_number(gv.area[std::size_t(G)] * gv.back[std::size_t(G)])});
    }
    write_csv_table(command.group_factors, {"from", "to", "F", "exchange_area"}, rows, run_id_of(summary));
    note("wrote " + command.group_factors);
  }
  // The groups' heat, largest first, on the report.
  std::vector<int> order(static_cast<std::size_t>(groups), 0);
  for (int G = 0; G < groups; ++G) order[std::size_t(G)] = G;
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return std::abs(group_Q[std::size_t(a)]) > std::abs(group_Q[std::size_t(b)]); });
  for (std::size_t k = 0; k < order.size() && k < 10; ++k) {
    const auto g = std::size_t(order[k]);
    const std::string se = error_note.empty() ? " (+- " + fmt(std::sqrt(group_Q_var[g]), "%.2g") + ")" : "";
    std::fprintf(report_stream(), "  %s %s: Q = %.6g W%s, area %.4g m^2, radiant temperature %.2f K\n",
                 command.group_by.c_str(), names[g].c_str(), group_Q[g], se.c_str(), gv.area[g],
                 std::pow(group_T4[g] / gv.area[g], 0.25));
  }
  if (order.size() > 10) std::fprintf(report_stream(), "  ... %zu more (--groups FILE.csv)\n", order.size() - 10);

  if (!command.sensitivities.empty())
    report_sensitivities(command.sensitivities, command.sensitivities_csv, command.group_by, input, problem.F, r,
                         group, names, traced, summary);

  // Per-patch outputs.
  std::vector<double> eps(n), given(n);
  for (std::size_t i = 0; i < n; ++i) {
    eps[i] = conditions[i].emissivity;
    given[i] = conditions[i].temperature_given ? 1 : 0;
  }
  fields.push_back(scalar_field("emissivity", eps));
  fields.push_back(scalar_field("temperature_given", given, FieldKind::count));
  fields.push_back(scalar_field("J", r.J));
  fields.push_back(scalar_field("J_se", J_se));
  fields.push_back(scalar_field("G", r.G));
  fields.push_back(scalar_field("q", r.q));
  fields.push_back(scalar_field("q_se", q_se));
  fields.push_back(scalar_field("Q", r.Q));
  fields.push_back(scalar_field("Q_se", Q_se));
  fields.push_back(scalar_field("T", r.T));
  fields.push_back(scalar_field("T_se", T_se));
  if (!disc.J.empty()) {
    const auto total = [](const std::vector<double>& se, const std::vector<double>& d) {
      std::vector<double> t(se.size());
      for (std::size_t i = 0; i < se.size(); ++i) t[i] = std::sqrt(se[i] * se[i] + d[i] * d[i]);
      return t;
    };
    fields.push_back(scalar_field("J_disc", disc.J));
    fields.push_back(scalar_field("J_err", total(J_se, disc.J)));
    fields.push_back(scalar_field("q_disc", disc.q));
    fields.push_back(scalar_field("q_err", total(q_se, disc.q)));
    fields.push_back(scalar_field("Q_disc", disc.Q));
    fields.push_back(scalar_field("Q_err", total(Q_se, disc.Q)));
    fields.push_back(scalar_field("T_disc", disc.T));
    fields.push_back(scalar_field("T_err", total(T_se, disc.T)));
  }
  fields.push_back(scalar_field("sky", input.sky));
  std::vector<double> contact(n);
  for (std::size_t i = 0; i < n; ++i) contact[i] = in_contact[i] ? 1 : 0;
  fields.push_back(scalar_field("contact", contact, FieldKind::count));
  if (traced) fields.push_back(scalar_field("back", back));
  VtpMetadata metadata = solution_metadata(solution, patches);
  metadata.set_text("solver", command.solver);
  metadata.set_real("ambient_temperature", command.ambient_temperature);
  metadata.set_real("sum_Q", total);
  write_outputs(command.scene, patches, fields, summary, metadata);
  if (solution.status == SolveStatus::converged) return 0;
  std::fprintf(stderr, "radwalk: %s did not converge: %s\n", solution.method.c_str(), solution.message.c_str());
  return solution.status == SolveStatus::max_iterations ? 1 : 3;
}

}  // namespace radwalk::app
