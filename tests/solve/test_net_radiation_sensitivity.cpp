// Sensitivities of the groups' net heat by the adjoint of the net-radiation system
// (solve/net_radiation_sensitivity.h, docs/theory/net_radiation.md "Sensitivities") against central finite
// differences of full solves on the unit cube with its exact F: emissivities and temperatures, with a re-radiating
// face, a black face, a group of two faces and an open cube (a face missing: the rest sees an ambient).
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <vector>

#include "solve/net_radiation.h"
#include "solve/net_radiation_sensitivity.h"
#include "support/reference_problems.h"

using namespace radwalk;

namespace {

// Six faces: different emissivities and temperatures, face 3 re-radiating (q = 0), face 4 black (eps = 1).
NetRadiationInput cube_input(const std::vector<int>& faces) {
  const double eps[6] = {0.9, 0.3, 0.55, 0.7, 1.0, 0.05};
  const double T[6] = {600, 300, 350, 0, 280, 450};
  NetRadiationInput in;
  for (int f : faces) {
    SurfaceCondition s;
    s.emissivity = eps[f];
    s.temperature = T[f];
    s.temperature_given = f != 3;
    in.surface.push_back(s);
    in.area.push_back(1.0);
  }
  return in;
}

// Q of every group by a full dense solve (dense_net_radiation, then net_radiation_result).
std::vector<double> group_Q(const NetRadiationInput& in, const SparseF& F, const std::vector<std::int32_t>& group,
                            int groups) {
  const NetRadiationResult r = net_radiation_result(in, F, dense_net_radiation(in, F));
  std::vector<double> Q(std::size_t(groups), 0.0);
  for (std::size_t i = 0; i < r.Q.size(); ++i) Q[std::size_t(group[i])] += r.Q[i];
  return Q;
}

// The central difference of every group's Q in a parameter of group H moved by +-step (eps or T of its
// known-temperature patches; eps of its known-flux patches too, which must not matter).
std::vector<double> central_difference(const NetRadiationInput& in, const SparseF& F,
                                       const std::vector<std::int32_t>& group, int groups, int H, bool eps,
                                       double step) {
  auto moved = [&](double by) {
    NetRadiationInput m = in;
    for (std::size_t i = 0; i < m.area.size(); ++i) {
      if (group[i] != H) continue;
      if (eps)
        m.surface[i].emissivity += by;
      else if (m.surface[i].temperature_given)
        m.surface[i].temperature += by;
    }
    return group_Q(m, F, group, groups);
  };
  const std::vector<double> up = moved(step), down = moved(-step);
  std::vector<double> d(static_cast<std::size_t>(groups));
  for (int G = 0; G < groups; ++G) d[std::size_t(G)] = (up[std::size_t(G)] - down[std::size_t(G)]) / (2 * step);
  return d;
}

void check_against_differences(const std::vector<int>& faces, const std::vector<std::int32_t>& group, int groups,
                               double ambient) {
  NetRadiationInput in = cube_input(faces);
  in.ambient_temperature = ambient;
  const SparseF F = test::unit_cube_F(faces);
  if (faces.size() < 6) {
    in.sky.resize(faces.size());
    for (std::size_t i = 0; i < faces.size(); ++i) in.sky[i] = 1 - double(F.row(Eigen::Index(i)).sum());
  }
  const NetRadiationResult r = net_radiation_result(in, F, dense_net_radiation(in, F));
  std::vector<int> responses;
  for (int G = 0; G < groups; ++G) responses.push_back(G);
  const NetRadiationSensitivity s = net_radiation_sensitivity(in, F, r, group, groups, responses);
  double Q_scale = 0;
  for (double Q : r.Q) Q_scale = std::max(Q_scale, std::abs(Q));
  // Tolerance of D(h) = (Q(p + h) - Q(p - h)) / 2h: truncation h^2 Q'''/6 + O(h^4), estimated from the step
  // doubled, |D(2h) - D(h)| / 3 (Richardson), taken twice; plus rounding: each Q carries about kappa eps_mach
  // Q_scale with kappa <= 1e3 for these 6 x 6 systems (cond(I - diag(rho) F) < 20 here), divided by h.
  const double eps_mach = std::numeric_limits<double>::epsilon();
  double largest_cross = 0, cross_tolerance = 0;
  for (int pass = 0; pass < 2; ++pass) {
    const bool eps = pass == 0;
    const double h = eps ? 1e-4 : 1e-2;  // emissivity, kelvin
    for (int H = 0; H < groups; ++H) {
      bool movable = true;  // eps + h must stay <= 1 for every patch of H
      for (std::size_t i = 0; i < faces.size(); ++i)
        if (group[i] == H && eps && in.surface[i].emissivity + 2 * h > 1) movable = false;
      if (!movable) continue;
      const std::vector<double> d1 = central_difference(in, F, group, groups, H, eps, h);
      const std::vector<double> d2 = central_difference(in, F, group, groups, H, eps, 2 * h);
      for (int G = 0; G < groups; ++G) {
        const double adjoint = eps ? s.dQ_deps(G, H) : s.dQ_dT(G, H);
        const double tol = 2 * std::abs(d2[std::size_t(G)] - d1[std::size_t(G)]) / 3 + 1e3 * eps_mach * Q_scale / h;
        INFO((eps ? "dQ/deps" : "dQ/dT") << " of group " << G << " in group " << H << ": adjoint " << adjoint
                                         << ", difference " << d1[std::size_t(G)] << ", tolerance " << tol);
        CHECK(std::abs(adjoint - d1[std::size_t(G)]) <= tol);
        if (G != H && std::abs(d1[std::size_t(G)]) > largest_cross)
          largest_cross = std::abs(d1[std::size_t(G)]), cross_tolerance = tol;
      }
    }
  }
  // The test can fail: the cross terms (G != H) are the adjoint's alone, and the largest is far above its
  // tolerance (an adjoint left at 0 would be rejected).
  INFO("largest cross sensitivity " << largest_cross << ", its tolerance " << cross_tolerance);
  CHECK(largest_cross > 100 * cross_tolerance);
  for (double res : s.residual) CHECK(res <= 1e-9);
}

}  // namespace

TEST_CASE("net radiation sensitivities: the closed cube, one group per face (a re-radiating and a black face), "
          "against central differences", "[net_radiation][sensitivity]") {
  check_against_differences({0, 1, 2, 3, 4, 5}, {0, 1, 2, 3, 4, 5}, 6, 0);
}

TEST_CASE("net radiation sensitivities: groups of several faces and an open cube with an ambient, against central "
          "differences", "[net_radiation][sensitivity]") {
  check_against_differences({0, 1, 2, 3, 4, 5}, {0, 0, 1, 2, 3, 3}, 4, 0);
  check_against_differences({0, 1, 2, 3, 5}, {0, 1, 2, 3, 4}, 5, 290);  // face z0 missing: an opening
}

TEST_CASE("net radiation sensitivities: a known-flux group's Q does not move, and its emissivity moves nothing",
          "[net_radiation][sensitivity]") {
  const std::vector<int> faces = {0, 1, 2, 3, 4, 5};
  const NetRadiationInput in = cube_input(faces);
  const SparseF F = test::unit_cube_F(faces);
  const NetRadiationResult r = net_radiation_result(in, F, dense_net_radiation(in, F));
  const std::vector<std::int32_t> group = {0, 1, 2, 3, 4, 5};
  const NetRadiationSensitivity s = net_radiation_sensitivity(in, F, r, group, 6, {3, 0});
  for (int H = 0; H < 6; ++H) {
    CHECK(std::abs(s.dQ_deps(0, H)) <= 1e-9);  // Q of the re-radiating face is given (0)
    CHECK(std::abs(s.dQ_dT(0, H)) <= 1e-9);
  }
  CHECK(s.dQ_deps(1, 3) == 0.0);  // the re-radiating face's emissivity changes only its own temperature
  CHECK(s.dQ_dT(1, 3) == 0.0);    // and its temperature is solved, not given
}
