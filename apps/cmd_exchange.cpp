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

#include "apps/exchange_sensitivities.h"
#include "apps/options.h"
#include "apps/pipeline.h"
#include "apps/run_metadata.h"
#include "core/error.h"
#include "core/format_number.h"
#include "core/parallel.h"
#include "formfactor/form_factor_noise.h"
#include "io/csv_writer.h"
#include "mesh/length_unit.h"
#include "patch/contact_patches.h"
#include "solve/form_factor_error.h"
#include "solve/group_view_factors.h"
#include "solve/heat_exchange.h"
#include "solve/net_radiation.h"
#include "solve/solve_radiosity.h"
#include "solve/surface_conditions.h"
#include "visibility/embree_visibility.h"
#include "walk/random_walk_solver.h"
#include "walk/walk_options.h"

namespace radwalk::app {
namespace {

SolveOptions solve_options(const ExchangeCommand& c, std::size_t patches) {
  SolveOptions o;
  o.solver = c.solver;
  o.auto_iterative = "gmres";  // re-radiating rows (rho = 1): docs/theory/net_radiation.md, "The Krylov solver"
  o.tol = c.tol;
  o.max_iterations = c.max_iterations > 0 ? c.max_iterations : default_max_iterations(c.solver, patches);
  return o;
}

}  // namespace

int run_exchange(const ExchangeCommand& command) {
  RunSummary summary("exchange", command.scene.argv);
  // sigma T^4 is in W/m^2, so areas must be in m^2: a named unit other than metres is refused (with the --scale that
  // converts it), an unnamed one is taken as metres.
  const std::string unit = length_unit(command.scene).length();
  if (unit != "m" && !command.scene.unit.empty())
    throw InputError("radwalk exchange works in metres (sigma T^4 is W/m^2) but the lengths are in " + unit +
                     ": use --unit " + command.scene.unit + " --scale " +
                     format_number(metres_per(command.scene.unit)) +
                     " (lengths times the scale become metres)");
  // Contact patches left out are whole patches (patch/contact_patches.h): the supports are cut along the
  // footprints first (the default), so that no patch of the floor reaches under a block, where its rays would start
  // inside it.
  if (command.contact_faces == "exclude" && !command.scene.contact_cut)
    throw InputError("--contact-faces exclude needs the supports cut along the contact footprints: remove "
                     "--no-contact-cut");
  const SceneOptions& scene_options = command.scene;
  Mesh mesh;
  std::vector<ContactRegion> regions;
  PatchSet patches = load_patches(scene_options, summary, mesh, &regions);
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

  HeatExchangeOptions options;
  options.solve = solve_options(command, n);
  options.ambient_temperature = command.ambient_temperature;
  options.exclude_contacts = command.contact_faces == "exclude";
  options.group_by = command.group_by;
  options.discretisation_directions = command.discretisation_directions;
  options.seed = command.scene.seed;
  WalkOptions walk = command.walk;
  if (command.solver == "random-walk") {
    walk.seed = command.scene.seed;
    walk.progress = true;
    check_walk_options(walk, n);
    options.solver = [&walk](const RadiosityProblem& p) { return solve_random_walk(p, nullptr, nullptr, walk); };
  }
  HeatExchange x = exchange_heat(patches, conditions, regions, std::move(ff), options);
  const bool traced = x.traced;
  const bool exclude = options.exclude_contacts;
  const NetRadiationInput& input = x.input;
  const RadiosityProblem& problem = x.problem;
  const Solution& solution = x.solution;
  const HeatBalance& bal = x.balance;
  if (!traced && bal.sky_area > 1e-6 * patches.total_area())
    note("form factors not traced here (analytic or read from a file): 1 - the row sum of F is taken as the sky "
         "view factor; backs of one-sided faces cannot be told from the sky");
  if (bal.sky_area > 1e-6 * patches.total_area() && command.ambient_temperature == 0 && !command.ambient_given)
    warn(summary, "part of the scene sees out (sky view factor x area = " + format_number(bal.sky_area) +
                      " m^2): escaping radiation reaches an ambient at 0 K; give --ambient-temperature T");
  // Patch description columns: the system's rho and source (E) of every patch.
  {
    const NetRadiationCoefficients& c = x.coefficients;
    for (std::size_t i = 0; i < n; ++i) {
      patches.rho[i] = Rgb::Constant(c.rho[i]);
      patches.E[i] = Rgb::Constant(c.source[i]);
    }
  }
  summary.add_timing("solve", solution.seconds);
  std::fprintf(report_stream(), "%s: %s (%s)", solution.method.c_str(), to_string(solution.status),
               solution.message.c_str());
  if (solution.iterations > 0) std::fprintf(report_stream(), ", %ld iterations", solution.iterations);
  if (solution.residual == solution.residual)
    std::fprintf(report_stream(), ", relative residual %.3g", solution.residual);
  std::fprintf(report_stream(), ", %.3f s\n", solution.seconds);
  summary.json()["solution"] = solution_json(solution);
  if (!x.solved) {
    if (!command.scene.json.empty()) summary.write(command.scene.json);
    std::fprintf(stderr, "radwalk: %s did not converge: %s\n", solution.method.c_str(), solution.message.c_str());
    return solution.status == SolveStatus::max_iterations ? 1 : 3;
  }
  const NetRadiationResult& r = x.result;
  const std::vector<double>& back = x.back;
  const std::vector<double>&J_se = x.J_se, &q_se = x.q_se, &Q_se = x.Q_se, &T_se = x.T_se;
  const std::string& error_note = x.error_note;
  summary.json()["exchange"]["error_method"] = x.error_method;

  // The discretisation error of J, q, Q, T and the totals sqrt(se^2 + disc^2).
  const ExchangeDiscretisation& disc = x.discretisation;
  if (!disc.J.empty()) {
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
    jd["points_per_patch"] = disc.points;
    jd["directions_per_point"] = disc.directions;
    jd["rays"] = disc.rays;
    jd["sweeps"] = disc.sweeps;
    jd["method"] = "the radiosity system's discretisation error e = (I - H)^-1 d (docs/theory/discretisation_error.md) "
                   "on the net-radiation problem, J_disc = sqrt((e_0 - e_1)^2 + (sd_0 + sd_1)^2); q, Q, T linearly "
                   "from J (docs/heat-exchange.md); black known-temperature patches: only J's part";
    jd["J_disc_max"] = J_disc_max;
    jd["J_disc_relative"] = relative;
    jd["Q_disc_sum"] = Q_disc_sum;
    std::fprintf(report_stream(),
                 "discretisation error (1 sd equivalent): J_disc up to %.3g W/m^2, %.3g %% of J (area-weighted RMS); "
                 "sum of |Q_disc| %.3g W; per patch J_disc, q_disc, Q_disc, T_disc and the totals J_err, q_err, "
                 "Q_err, T_err = sqrt(se^2 + disc^2)\n",
                 J_disc_max, 100 * relative, Q_disc_sum);
  }

  // The energy balance (solve/heat_exchange.h, step 6).
  const double total = bal.sum_Q, total_se = bal.sum_Q_se, to_ambient = bal.to_ambient,
               from_ambient = bal.from_ambient, into_backs = bal.into_backs, residual = bal.residual;
  auto& jx = summary.json()["exchange"];
  jx["stefan_boltzmann"] = kStefanBoltzmann;
  jx["ambient_temperature"] = command.ambient_temperature;
  jx["length_unit"] = length_unit(command.scene).length();
  jx["sum_Q"] = total;
  jx["sum_Q_se"] = total_se;
  jx["to_ambient"] = to_ambient;
  jx["to_ambient_se"] = bal.to_ambient_se;
  jx["from_ambient"] = from_ambient;
  jx["lost_to_back_faces"] = into_backs;
  jx["lost_to_back_faces_se"] = bal.into_backs_se;
  jx["balance_residual"] = residual;
  jx["balance_residual_se"] = bal.residual_se;
  jx["sky_area"] = bal.sky_area;
  if (traced && error_note.empty()) {
    std::fprintf(report_stream(),
                 "energy balance: sum of Q = %.6g W (+- %.2g); to the ambient %.6g W (+- %.2g), from it %.6g W; lost "
                 "into the backs of one-sided faces %.6g W (+- %.2g); residual %.3g W (+- %.2g, the form factors' "
                 "reciprocity defect)\n",
                 total, total_se, to_ambient, bal.to_ambient_se, from_ambient, into_backs, bal.into_backs_se, residual,
                 bal.residual_se);
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
    warn(summary,
         format_number(into_backs) + " W (+- " + format_number(bal.into_backs_se, 2) +
             ") is radiated into the backs of one-sided faces, where it is lost (absorbed at 0 K): faces "
             "oriented the wrong way (--orient outward), or open and thin parts that should be two-sided "
             "(--open-shells two-sided, 'radwalk_two_sided 1', --two-sided); the back_hits field says where");

  // The contact patches' share, W.
  {
    jx["contact_patches"] = x.contact_count;
    jx["contact_area"] = x.contact_area;
    jx["contact_faces"] = command.contact_faces;
    jx["contact_radiated"] = x.contact_radiated;
    jx["contact_Q"] = x.contact_Q;
    if (x.contact_count > 0 && !exclude)
      warn(
          summary,
          std::to_string(x.contact_count) + " patches (" + format_number(x.contact_area) +
              " m^2) touch another "
              "surface (faces lying on a support, e.g. furniture bottoms on the floor, and the support under "
              "them): they radiate " +
              format_number(x.contact_radiated) +
              " W into the backs of faces or out through the "
              "support, and their net heat is " +
              format_number(x.contact_Q) +
              " W, which in reality is conduction "
              "through the contact; --contact-faces exclude leaves them out of the exchange");
    else if (x.contact_count > 0)
      note(std::to_string(x.contact_count) + " contact patches (" + format_number(x.contact_area) +
           " m^2) left out of the exchange");
  }

  // Closed cavities (solve/heat_exchange.h, step 2b): one warning each, and the list in the JSON.
  {
    nlohmann::json list = nlohmann::json::array();
    for (const HeatExchangeCavity& c : x.cavities) {
      warn(summary, cavity_warning(c));
      list.push_back({{"patches", c.cavity.patches.size()},
                      {"area", c.cavity.area},
                      {"leak", c.cavity.leak},
                      {"given_Q", c.cavity.given_Q},
                      {"objects", c.objects},
                      {"groups", c.groups},
                      {"materials", c.materials},
                      {"first_patch", c.cavity.patches.front()}});
    }
    jx["cavities"] = list;
    jx["cavity_leak_threshold"] = kCavityLeak;
  }

  // Per-group tables.
  const std::vector<std::string>& names = x.groups.names;
  const std::vector<std::int32_t>& group = x.groups.group;
  const int groups = int(names.size());
  const GroupViewFactors& gv = x.groups.view_factors;
  const std::vector<double>& group_Q = x.groups.Q;
  const std::vector<double>& group_Q_se = x.groups.Q_se;
  const std::vector<double>& group_T = x.groups.T_radiant;
  nlohmann::json table = nlohmann::json::array();
  for (int G = 0; G < groups; ++G) {
    const auto g = std::size_t(G);
    table.push_back({{"name", names[g]},
                     {"area", gv.area[g]},
                     {"Q", group_Q[g]},
                     {"Q_se", group_Q_se[g]},
                     {"T_radiant", group_T[g]},
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
      rows.push_back({csv_text(names[g]), csv_number(gv.area[g]), csv_number(group_Q[g]), csv_number(group_Q_se[g]),
                      csv_number(group_T[g]), csv_number(gv.sky[g]), csv_number(gv.back[g])});
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
    const std::string se = error_note.empty() ? " (+- " + format_number(group_Q_se[g], 2) + ")" : "";
    const std::string T = std::isfinite(group_T[g])
                              ? format_number(group_T[g], 2, NumberNotation::fixed) + " K"
                              : std::string("none (no patch of it radiates)");
    std::fprintf(report_stream(), "  %s %s: Q = %.6g W%s, area %.4g m^2, radiant temperature %s\n",
                 command.group_by.c_str(), names[g].c_str(), group_Q[g], se.c_str(), gv.area[g], T.c_str());
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
  // A closed cavity's J, G and T (and their errors) have no value (solve/heat_exchange.h, step 2b).
  const auto missing = [&x](const std::vector<double>& v) { return undetermined_as_missing(v, x); };
  fields.push_back(scalar_field("J", missing(r.J)));
  fields.push_back(scalar_field("J_se", missing(J_se)));
  fields.push_back(scalar_field("G", missing(r.G)));
  fields.push_back(scalar_field("q", r.q));
  fields.push_back(scalar_field("q_se", q_se));
  fields.push_back(scalar_field("Q", r.Q));
  fields.push_back(scalar_field("Q_se", Q_se));
  fields.push_back(scalar_field("T", missing(r.T)));
  fields.push_back(scalar_field("T_se", missing(T_se)));
  if (!disc.J.empty()) {
    const auto total = [](const std::vector<double>& se, const std::vector<double>& d) {
      std::vector<double> t(se.size());
      for (std::size_t i = 0; i < se.size(); ++i) t[i] = std::sqrt(se[i] * se[i] + d[i] * d[i]);
      return t;
    };
    fields.push_back(scalar_field("J_disc", missing(disc.J)));
    fields.push_back(scalar_field("J_err", missing(total(J_se, disc.J))));
    fields.push_back(scalar_field("q_disc", disc.q));
    fields.push_back(scalar_field("q_err", total(q_se, disc.q)));
    fields.push_back(scalar_field("Q_disc", disc.Q));
    fields.push_back(scalar_field("Q_err", total(Q_se, disc.Q)));
    fields.push_back(scalar_field("T_disc", missing(disc.T)));
    fields.push_back(scalar_field("T_err", missing(total(T_se, disc.T))));
  }
  fields.push_back(scalar_field("sky", input.sky));
  std::vector<double> contact(n);
  for (std::size_t i = 0; i < n; ++i) contact[i] = x.in_contact[i] ? 1 : 0;
  fields.push_back(scalar_field("contact", contact, FieldKind::count));
  std::vector<double> in_cavity(n);
  for (std::size_t i = 0; i < n; ++i) in_cavity[i] = x.cavity[i] >= 0 ? 1 : 0;
  fields.push_back(scalar_field("cavity", in_cavity, FieldKind::count));
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
