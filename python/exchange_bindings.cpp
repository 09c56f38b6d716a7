// radwalk.exchange: grey diffuse radiative heat exchange (solve/heat_exchange.h), the pipeline of
// `radwalk exchange`, with its per-patch fields, group tables and energy balance as numpy arrays and dicts.
#include <cmath>
#include <memory>

#include "bindings.h"
#include "core/error.h"
#include "core/parallel.h"
#include "interruptible.h"
#include "solve/heat_exchange.h"
#include "solve/surface_conditions.h"

namespace radwalk::python {
namespace {

struct ExchangeResult {
  HeatExchange x;
  std::map<std::string, double> timings;
};

py::array_t<double> copy_of(const std::vector<double>& v) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

// sqrt(se^2 + disc^2) per patch (se where disc is not estimated).
std::vector<double> total_of(const std::vector<double>& se, const std::vector<double>& disc) {
  if (disc.empty()) return se;
  std::vector<double> t(se.size());
  for (std::size_t i = 0; i < se.size(); ++i) t[i] = std::sqrt(se[i] * se[i] + disc[i] * disc[i]);
  return t;
}

ExchangeResult exchange(const Scene& scene, const py::object& F, const std::string& solver, double tol,
                        long max_iterations, long rays, std::uint64_t seed, long long threads_arg,
                        double ambient_temperature, const std::string& contact_faces, const std::string& group_by,
                        int discretisation_directions) {
  // Every option checked before any form factor is traced.
  if (solver == "random-walk")
    throw InputError("solver='random-walk' is not in radwalk.exchange yet: use `radwalk exchange --solver "
                     "random-walk` (the walks' method and counts are its options), or a deterministic solver here");
  if (contact_faces != "include" && contact_faces != "exclude")
    throw InputError("contact_faces must be 'include' or 'exclude', got '" + contact_faces + "'");
  if (group_by != "object" && group_by != "group" && group_by != "material")
    throw InputError("group_by must be 'object', 'group' or 'material', got '" + group_by + "'");
  if (discretisation_directions < 0)
    throw InputError("discretisation_directions must be >= 0 (0: not estimated), got " +
                     std::to_string(discretisation_directions));
  if (!(ambient_temperature >= 0) || !std::isfinite(ambient_temperature))
    throw InputError("ambient_temperature must be a finite temperature >= 0 K, got " +
                     std::to_string(ambient_temperature));
  // Excluded contact patches must be whole patches of the footprint (the CLI cuts the supports along the
  // footprints for --contact-faces exclude): a scene patched without the cut cannot honour it.
  if (contact_faces == "exclude" && !scene.contact_regions.empty() && !scene.cut)
    throw InputError("contact_faces='exclude' needs the supports cut along the contact footprints: load the scene "
                     "with max_edge or max_area and contact_cut=True (the default; as `radwalk exchange "
                     "--contact-faces exclude` does), otherwise floor patches reaching under an object would shoot "
                     "rays from inside it");
  const std::vector<SurfaceCondition> conditions = surface_conditions(scene.patches);
  const int threads = check_run(scene, threads_arg);
  ExchangeResult out;
  FormFactors ff;
  SparseF f = form_factor_matrix(F, scene, rays, seed, threads, out.timings, &ff);
  ff.F = std::move(f);
  interruptible([&] {
    ThreadLimit limit(threads);
    HeatExchangeOptions o;
    o.solve.solver = solver;
    o.solve.auto_iterative = "gmres";  // as the CLI's exchange (docs/theory/net_radiation.md, "The Krylov solver")
    o.solve.tol = tol;
    o.solve.max_iterations = max_iterations > 0 ? max_iterations : default_max_iterations(solver, scene.patches.size());
    o.ambient_temperature = ambient_temperature;
    o.exclude_contacts = contact_faces == "exclude";
    o.group_by = group_by;
    o.discretisation_directions = discretisation_directions;
    o.seed = seed;
    out.x = exchange_heat(scene.patches, conditions, scene.contact_regions, std::move(ff), o);
  });
  check_solved(out.x.solution);
  for (const HeatExchangeCavity& c : out.x.cavities)  // the CLI's warning, one each
    if (PyErr_WarnEx(PyExc_UserWarning, cavity_warning(c).c_str(), 1) != 0) throw py::error_already_set();
  out.timings["solve"] = out.x.solution.seconds;
  if (!out.x.discretisation.J.empty()) out.timings["discretisation_error"] = out.x.discretisation.seconds;
  return out;
}

}  // namespace

void bind_exchange(py::module_& m) {
  py::class_<ExchangeResult>(m, "Exchange", R"doc(What radwalk.exchange returns (docs/heat-exchange.md).

Per patch (N,) float64 arrays (copies): J (radiosity, W/m^2), G (irradiance), q (net flux leaving, W/m^2), Q (net
heat, W), T (K; solved where a heat flux was given), each with its statistical standard error (J_se, q_se, Q_se,
T_se: the traced form factors' noise, first order; zero when F was not traced by radwalk), its discretisation error
(J_disc, q_disc, Q_disc, T_disc; None when discretisation_directions = 0) and the total (J_err, ...: sqrt(se^2 +
disc^2)); emissivity, temperature_given, sky (view factor to the ambient), back (fraction into backs of one-sided
faces), contact (1 for a contact patch), cavity (1 for a patch of a closed cavity: radiation leaves its J, G and T
undetermined, NaN in those arrays and their errors; docs/heat-exchange.md, "Closed cavities"; one UserWarning per
cavity, and the list in cavities). These are the columns of the CLI's CSV with the same names (NaN where the CSV
has an empty cell). groups' T_radiant is None for a group none of whose patches radiates.
groups: a list of dicts {name, area, Q, Q_se, T_radiant, sky, back} (the CLI's --groups CSV); group_names and
group_factors ((G, G) array F_GH, the CLI's --group-factors); balance: a dict of the energy balance in W (sum_Q,
sum_Q_se, to_ambient, to_ambient_se, from_ambient, lost_to_back_faces, lost_to_back_faces_se, balance_residual,
balance_residual_se, sky_area, contact_patches, contact_area, contact_radiated, contact_Q: the CLI's JSON keys);
method, status, message, iterations, residual: the solve; error_method; timings.)doc")
      .def_property_readonly("J", [](const ExchangeResult& r) { return copy_of(undetermined_as_missing(r.x.result.J, r.x)); },
          "Radiosity J (N,) float64 per patch, W/m^2 (a copy).")
      .def_property_readonly("G", [](const ExchangeResult& r) { return copy_of(undetermined_as_missing(r.x.result.G, r.x)); },
          "Irradiance G (N,) float64 per patch, W/m^2 (a copy).")
      .def_property_readonly("q", [](const ExchangeResult& r) { return copy_of(r.x.result.q); },
          "Net heat flux q (N,) float64 per patch, W/m^2, leaving the surface (a copy).")
      .def_property_readonly("Q", [](const ExchangeResult& r) { return copy_of(r.x.result.Q); },
          "Net heat Q = A q (N,) float64 per patch, W, leaving the surface (a copy).")
      .def_property_readonly("T", [](const ExchangeResult& r) { return copy_of(undetermined_as_missing(r.x.result.T, r.x)); },
          "Temperature T (N,) float64 per patch, K: given, or solved where a heat flux was given (a copy).")
      .def_property_readonly("J_se", [](const ExchangeResult& r) { return copy_of(undetermined_as_missing(r.x.J_se, r.x)); },
          "Statistical standard error of J (N,) float64, W/m^2, from the traced form factors' noise (zeros when F was not traced by radwalk).")
      .def_property_readonly("q_se", [](const ExchangeResult& r) { return copy_of(r.x.q_se); },
          "Statistical standard error of q (N,) float64, W/m^2 (zeros when F was not traced by radwalk).")
      .def_property_readonly("Q_se", [](const ExchangeResult& r) { return copy_of(r.x.Q_se); },
          "Statistical standard error of Q (N,) float64, W (zeros when F was not traced by radwalk).")
      .def_property_readonly("T_se", [](const ExchangeResult& r) { return copy_of(undetermined_as_missing(r.x.T_se, r.x)); },
          "Statistical standard error of T (N,) float64, K, where T is solved (zeros elsewhere).")
      .def_property_readonly("J_disc", [](const ExchangeResult& r) -> py::object {
        return r.x.discretisation.J.empty() ? py::object(py::none()) : py::object(copy_of(undetermined_as_missing(r.x.discretisation.J, r.x)));
      },
          "Discretisation error of J (N,) float64, W/m^2 (1 standard deviation equivalent); None when not estimated.")
      .def_property_readonly("q_disc", [](const ExchangeResult& r) -> py::object {
        return r.x.discretisation.q.empty() ? py::object(py::none()) : py::object(copy_of(r.x.discretisation.q));
      },
          "Discretisation error of q (N,) float64, W/m^2; None when not estimated.")
      .def_property_readonly("Q_disc", [](const ExchangeResult& r) -> py::object {
        return r.x.discretisation.Q.empty() ? py::object(py::none()) : py::object(copy_of(r.x.discretisation.Q));
      },
          "Discretisation error of Q (N,) float64, W; None when not estimated.")
      .def_property_readonly("T_disc", [](const ExchangeResult& r) -> py::object {
        return r.x.discretisation.T.empty() ? py::object(py::none()) : py::object(copy_of(undetermined_as_missing(r.x.discretisation.T, r.x)));
      },
          "Discretisation error of T (N,) float64, K; None when not estimated.")
      .def_property_readonly("J_err", [](const ExchangeResult& r) { return copy_of(undetermined_as_missing(total_of(r.x.J_se, r.x.discretisation.J), r.x)); },
          "Total error sqrt(J_se^2 + J_disc^2) (N,) float64, W/m^2 (J_se when J_disc is not estimated).")
      .def_property_readonly("q_err", [](const ExchangeResult& r) { return copy_of(total_of(r.x.q_se, r.x.discretisation.q)); },
          "Total error sqrt(q_se^2 + q_disc^2) (N,) float64, W/m^2 (q_se when q_disc is not estimated).")
      .def_property_readonly("Q_err", [](const ExchangeResult& r) { return copy_of(total_of(r.x.Q_se, r.x.discretisation.Q)); },
          "Total error sqrt(Q_se^2 + Q_disc^2) (N,) float64, W (Q_se when Q_disc is not estimated).")
      .def_property_readonly("T_err", [](const ExchangeResult& r) { return copy_of(undetermined_as_missing(total_of(r.x.T_se, r.x.discretisation.T), r.x)); },
          "Total error sqrt(T_se^2 + T_disc^2) (N,) float64, K (T_se when T_disc is not estimated).")
      .def_property_readonly("emissivity",
                             [](const ExchangeResult& r) {
                               std::vector<double> e;
                               for (const SurfaceCondition& c : r.x.given) e.push_back(c.emissivity);
                               return copy_of(e);
                             },
          "Emissivity (N,) float64 per patch, as its material gives it.")
      .def_property_readonly("temperature_given",
                             [](const ExchangeResult& r) {
                               std::vector<double> e;
                               for (const SurfaceCondition& c : r.x.given) e.push_back(c.temperature_given ? 1 : 0);
                               return copy_of(e);
                             },
          "(N,) float64 per patch: 1 where the temperature is given (q solved), 0 where the heat flux is.")
      .def_property_readonly("sky", [](const ExchangeResult& r) { return copy_of(r.x.input.sky); },
          "Sky view factor (N,) float64 per patch: the fraction of its rays reaching the ambient (1 - row sum for a caller's F).")
      .def_property_readonly("back", [](const ExchangeResult& r) { return copy_of(r.x.back); },
          "(N,) float64 per patch: the fraction of its rays reaching the backs of one-sided faces (and excluded contact patches).")
      .def_property_readonly("contact",
                             [](const ExchangeResult& r) {
                               std::vector<double> c;
                               for (bool b : r.x.in_contact) c.push_back(b ? 1 : 0);
                               return copy_of(c);
                             },
          "(N,) float64 per patch: 1 for a patch in contact with another surface (patch/contact_patches.h), else 0.")
      .def_property_readonly("cavity",
                             [](const ExchangeResult& r) {
                               std::vector<double> c;
                               for (std::int32_t k : r.x.cavity) c.push_back(k >= 0 ? 1 : 0);
                               return copy_of(c);
                             },
          "(N,) float64 per patch: 1 for a patch of a closed cavity (J, G, T and their errors NaN there: undetermined), else 0.")
      .def_property_readonly("cavities",
                             [](const ExchangeResult& r) {
                               py::list out;
                               for (const HeatExchangeCavity& c : r.x.cavities) {
                                 py::dict d;
                                 d["patches"] = c.cavity.patches;
                                 d["area"] = c.cavity.area;
                                 d["leak"] = c.cavity.leak;
                                 d["given_Q"] = c.cavity.given_Q;
                                 d["objects"] = c.objects;
                                 d["groups"] = c.groups;
                                 d["materials"] = c.materials;
                                 out.append(d);
                               }
                               return out;
                             },
          "The closed cavities: a list of dicts {patches (indices), area, leak, given_Q, objects, groups, materials}, as the CLI's JSON exchange.cavities (which gives the number of patches and the first).")
      .def_property_readonly("group_names", [](const ExchangeResult& r) { return r.x.groups.names; },
          "The names of the groups (objects, groups or materials under group_by), in the order of groups and group_factors.")
      .def_property_readonly("group_factors",
                             [](const ExchangeResult& r) {
                               const Eigen::MatrixXd& F = r.x.groups.view_factors.F;
                               py::array_t<double> a({F.rows(), F.cols()});
                               auto v = a.mutable_unchecked<2>();
                               for (Eigen::Index i = 0; i < F.rows(); ++i)
                                 for (Eigen::Index j = 0; j < F.cols(); ++j) v(i, j) = F(i, j);
                               return a;
                             },
          "View factors between groups F_GH, a (G, G) float64 array (rows: from, columns: to), as the CLI's --group-factors.")
      .def_property_readonly("groups",
                             [](const ExchangeResult& r) {
                               py::list out;
                               const HeatExchangeGroups& g = r.x.groups;
                               for (std::size_t k = 0; k < g.names.size(); ++k) {
                                 py::dict d;
                                 d["name"] = g.names[k];
                                 d["area"] = g.view_factors.area[k];
                                 d["Q"] = g.Q[k];
                                 d["Q_se"] = g.Q_se[k];
                                 d["T_radiant"] = std::isfinite(g.T_radiant[k]) ? py::object(py::float_(g.T_radiant[k]))
                                                                                : py::object(py::none());
                                 d["sky"] = g.view_factors.sky[k];
                                 d["back"] = g.view_factors.back[k];
                                 out.append(d);
                               }
                               return out;
                             },
          "The table per group: a list of dicts {name, area, Q, Q_se, T_radiant, sky, back}, as the CLI's --groups CSV.")
      .def_property_readonly("balance",
                             [](const ExchangeResult& r) {
                               const HeatBalance& b = r.x.balance;
                               py::dict d;
                               d["sum_Q"] = b.sum_Q;
                               d["sum_Q_se"] = b.sum_Q_se;
                               d["to_ambient"] = b.to_ambient;
                               d["to_ambient_se"] = b.to_ambient_se;
                               d["from_ambient"] = b.from_ambient;
                               d["lost_to_back_faces"] = b.into_backs;
                               d["lost_to_back_faces_se"] = b.into_backs_se;
                               d["balance_residual"] = b.residual;
                               d["balance_residual_se"] = b.residual_se;
                               d["sky_area"] = b.sky_area;
                               d["contact_patches"] = r.x.contact_count;
                               d["contact_area"] = r.x.contact_area;
                               d["contact_radiated"] = r.x.contact_radiated;
                               d["contact_Q"] = r.x.contact_Q;
                               return d;
                             },
          "The energy balance in W as a dict with the CLI's JSON keys (sum_Q, ..., balance_residual, balance_residual_se, contact_*).")
      .def_property_readonly("method", [](const ExchangeResult& r) { return r.x.solution.method; },
          "The solver that ran (the CLI's JSON solution.method).")
      .def_property_readonly("status", [](const ExchangeResult& r) { return std::string(to_string(r.x.solution.status)); },
          "The solve's status: 'converged' or 'max-iterations'.")
      .def_property_readonly("message", [](const ExchangeResult& r) { return r.x.solution.message; },
          "The solver's own message (what it did, why it stopped).")
      .def_property_readonly("iterations", [](const ExchangeResult& r) { return r.x.solution.iterations; },
          "Iterations (sweeps) of the solver; 0 for the direct solve.")
      .def_property_readonly("residual", [](const ExchangeResult& r) { return r.x.solution.residual; },
          "Relative residual of the solve (NaN when not computed).")
      .def_property_readonly("error_method", [](const ExchangeResult& r) { return r.x.error_method; },
          "How the statistical errors were obtained, or 'not included: ...' and why.")
      .def_readonly("timings", &ExchangeResult::timings, "Stage name -> seconds (form factors, solve, error estimates).");

  m.def("exchange", &exchange, py::arg("scene"), py::arg("F") = py::none(), py::arg("solver") = "auto",
        py::arg("tol") = 1e-12, py::arg("max_iterations") = 0, py::arg("rays") = 1000, py::arg("seed") = 1,
        py::arg("threads") = 0, py::arg("ambient_temperature") = 0.0, py::arg("contact_faces") = "include",
        py::arg("group_by") = "object", py::arg("discretisation_directions") = 16,
        R"doc(Grey diffuse radiative heat exchange by the net-radiation method, as `radwalk exchange SCENE` (one library
pipeline, solve/heat_exchange.h; docs/heat-exchange.md): an Exchange with J, q, Q, T per patch and their errors,
the table per group, the view factors between groups and the energy balance.

scene: a Scene in metres whose materials give radwalk_emissivity and radwalk_temperature or radwalk_heat_flux.
F: a FormFactors (form_factors), a scipy.sparse (N, N) matrix or (N, N) array, or None: traced here with `rays`
  rays per patch and `seed`, as the CLI's --rays R --seed S (then the statistical errors and the balance's error
  bars are estimated; for a caller's matrix 1 - its row sum is the sky view factor and no errors are given).
solver: "auto" (direct up to 2000 patches, else GMRES), "direct", "gmres", "gauss-seidel", "jacobi",
  "southwell"; tol, max_iterations (0: the solver's default): as --tol, --max-iterations.
ambient_temperature: K, what escaping rays reach (--ambient-temperature).
contact_faces: "include" or "exclude" (--contact-faces); "exclude" needs a scene cut along its contacts (loaded with
  max_edge or max_area, contact_cut=True being the default) and is refused otherwise.
group_by: "object", "group" or "material"; discretisation_directions: 0 to skip the discretisation error.
Raises radwalk.InputError for bad options or thermal statements (the CLI's message); radwalk.NumericalError when
the solve diverged or was refused.)doc");
}

}  // namespace radwalk::python
