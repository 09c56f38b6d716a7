#pragma once
// Grey diffuse radiative heat exchange of a patched scene, from its form factors to every per-patch, per-group and
// balance figure with its error: the one pipeline of `radwalk exchange` (apps/cmd_exchange.cpp) and the Python
// `radwalk.exchange` (python/exchange_bindings.cpp). The physics: solve/net_radiation.h and
// docs/theory/net_radiation.md; the user's guide: docs/heat-exchange.md.
//
// Steps, for patches with their thermal conditions (solve/surface_conditions.h) and form factors ff:
//   1. where the rays not caught by F go: traced F (ff.rays per patch): s_i = escaped_i / n_i reaches the ambient,
//      b_i = back_hits_i / n_i the backs of one-sided faces; analytic or read F: s_i = 1 - row sum, b_i = 0;
//   2. contact patches (patch/contact_patches.h): flagged; with exclude_contacts their rows and columns of F are
//      removed, what other patches sent to them counted with the backs (b_i += F_ij), and they get J = q = Q = 0;
//   2b. closed cavities (solve/closed_cavities.h): components of known-flux patches that exchange less than
//      kCavityLeak of their radiation with anything else, so that radiation leaves their J undetermined (any
//      uniform value solves a re-radiating one); removed from the system as contact patches are (rows and
//      columns of F, what others sent them counted with the backs, J = 0 inside the solve), their q and Q the
//      given ones, their J, G and T (and errors) no value (`undetermined_as_missing`), left out of the energy
//      balance and of the groups' radiant temperatures;
//   3. the net-radiation system solved by options.solve;
//   4. statistical errors from the traced F's noise (first order): J_se by the propagation of each row's gather
//      variance (solve/form_factor_error.h); then linearly
//        known T, eps < 1: se(q) = eps / (1 - eps) se(J);  known T, eps = 1: se(q) = sqrt(V_G + (F se(J))^2);
//        known q: se(T) = se(J) / (4 sigma T^3);  se(Q) = A se(q);
//   5. the discretisation error (solve/exchange_discretisation.h) when discretisation_directions > 0;
//   6. the energy balance, W:  sum_i Q_i = (to the ambient) - (from the ambient) + (into backs) + R, with
//        R = sum_i A_i sum_j F_ij (J_i - J_j) - sum_i A_i J_i (1 - r_i - s_i - b_i)   (r_i the row sum of F)
//      the reciprocity defect of F, and its standard error from each row's rays, J held fixed, first order:
//        Var(R) = sum_i A_i^2 (sum_j F_ij (J_i - J_j)^2 - (sum_j F_ij (J_i - J_j))^2) / n_i;
//   7. per group (object, group or material): Q, its standard error, the radiant temperature
//      (sum A T^4 / sum A)^(1/4) over the group's patches that radiate: not contact patches, not in a closed
//      cavity, and seeing a surface or the ambient (row sum of F plus sky view factor > 0); NaN, no value (JSON null,
//      an empty CSV cell, None in Python), when none does (`radiating_area` 0). Then the view factors between
//      groups (solve/group_view_factors.h).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/solution.h"
#include "formfactor/form_factors.h"
#include "patch/contact_patches.h"
#include "patch/patch_set.h"
#include "solve/closed_cavities.h"
#include "solve/exchange_discretisation.h"
#include "solve/group_view_factors.h"
#include "solve/net_radiation.h"
#include "solve/solve_options.h"

namespace radwalk {

struct HeatExchangeOptions {
  SolveOptions solve;                    // the net-radiation system's solver (solve_radiosity) ...
  // ... or, when set, this one (the CLI's and Python's random walks on the matrix kernel, a layer above): a
  // Monte Carlo solver's own standard errors (Solution::B_se, N x 3) are added to J's.
  std::function<Solution(const RadiosityProblem&)> solver;
  double ambient_temperature = 0;        // K, of what the escaping rays reach (emissivity 1)
  bool exclude_contacts = false;         // step 2
  std::string group_by = "object";       // "object" | "group" | "material"
  int discretisation_directions = 16;    // 0: no discretisation error
  std::uint64_t seed = 1;                // of the discretisation error's rays
};

struct HeatBalance {
  double sum_Q = 0, sum_Q_se = 0;                // W
  double to_ambient = 0, to_ambient_se = 0;      // sum_i A_i J_i s_i
  double from_ambient = 0;                       // sum_i A_i s_i sigma T_a^4
  double into_backs = 0, into_backs_se = 0;      // sum_i A_i J_i b_i
  double residual = 0, residual_se = 0;          // R and its standard error (0 when F was not traced)
  double sky_area = 0;                           // sum_i A_i s_i, m^2
};

struct HeatExchangeGroups {
  std::vector<std::string> names;     // in order of first patch
  std::vector<std::int32_t> group;    // per patch
  GroupViewFactors view_factors;
  std::vector<double> Q, Q_se, T_radiant;
  std::vector<double> radiating_area;  // m^2 per group: the patches T_radiant is taken over (0: no T_radiant)
};

// A closed cavity (step 2b) with the names of what it belongs to.
struct HeatExchangeCavity {
  ClosedCavity cavity;
  std::vector<std::string> objects, groups, materials;  // distinct names of its patches, in patch order
};

// The one-line warning of a cavity: its objects and groups, patches, area, leak fraction, what is left out and
// why (shared by the CLI and Python).
std::string cavity_warning(const HeatExchangeCavity& c);

struct HeatExchange {
  NetRadiationInput input;            // the conditions used (excluded contact patches and cavities: black at
                                      // 0 K, s = 0)
  std::vector<SurfaceCondition> given;  // the conditions as the materials give them
  NetRadiationCoefficients coefficients;  // rho and source S of the system per patch (its E)
  RadiosityProblem problem;           // its F with the contact rows and columns removed when excluded
  Solution solution;                  // of the solver; J is valid only when solution.B has N rows
  bool solved = false;                // solution.B has N rows
  NetRadiationResult result;          // J, G, q, Q, T (empty unless solved)
  std::vector<double> back;           // b_i per patch (step 1 and 2)
  std::vector<double> J_se, q_se, Q_se, T_se;  // step 4 (zero when not estimated)
  std::string error_note;             // "" when step 4 ran, else why not
  std::string error_method;           // how the statistical errors were obtained (or "not included: ...")
  ExchangeDiscretisation discretisation;  // step 5 (empty vectors when not asked)
  bool traced = false;                // F came with its rays (ff.rays per patch)
  std::vector<bool> in_contact;       // step 2
  std::size_t contact_count = 0;
  double contact_area = 0, contact_radiated = 0, contact_Q = 0;  // m^2, W (sum A J), W (sum Q)
  std::vector<HeatExchangeCavity> cavities;  // step 2b
  std::vector<std::int32_t> cavity;   // per patch: its index in cavities, -1 for none
  HeatBalance balance;                // step 6 (cavities left out)
  HeatExchangeGroups groups;          // step 7
};

// A per-patch quantity for the outputs with the patches of closed cavities, where it is undetermined (J, G, T and
// their errors), set to NaN: the per-patch writers' "no value" (an empty CSV cell, docs/units-and-formats.md; in
// the .vtp VTK's NaN, shown in ParaView's NaN colour), the `cavity` field saying why.
std::vector<double> undetermined_as_missing(std::vector<double> v, const HeatExchange& x);

// Steps 1 to 7. conditions: per patch (surface_conditions); regions: the scene's contact regions (from
// patch_scene). ff is consumed (its F moves into the result's problem). Throws InputError for bad conditions or
// options (net_radiation_coefficients, an unknown group_by). When the solver does not converge, returns with
// solved = false after step 3 (the caller reports solution.status).
HeatExchange exchange_heat(const PatchSet& patches, const std::vector<SurfaceCondition>& conditions,
                           const std::vector<ContactRegion>& regions, FormFactors ff,
                           const HeatExchangeOptions& options);

}  // namespace radwalk
