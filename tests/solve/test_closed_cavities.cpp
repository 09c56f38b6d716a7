// Closed cavities of the net-radiation system (solve/closed_cavities.h, docs/heat-exchange.md, "Closed
// cavities"): a re-radiating unit cube whose faces see only one another is one, whatever lies outside it; the
// same cube with an opening to a black surface is one only while the opening passes less than kCavityLeak of
// its radiation, and above that its radiosity is determined: the cube comes to the temperature of what it
// sees through the opening.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "solve/closed_cavities.h"
#include "solve/net_radiation.h"
#include "support/reference_problems.h"

using namespace radwalk;

namespace {

// Patches 0-5: the unit cube's faces (area 1), re-radiating (q = 0, eps 0.8; face 0's flux `q0`), each row
// keeping 1 - lambda inside the cube and sending lambda to patch 6. Patch 6: a black surface (eps 1) at 300 K
// of area 100 outside, its row reciprocal (A_6 F_6i = A_i F_i6 = lambda), the rest of it to the sky at 0 K.
struct LeakyCube {
  NetRadiationInput input;
  SparseF F;
};
LeakyCube leaky_cube(double lambda, double q0 = 0) {
  LeakyCube c;
  const SparseF cube = test::unit_cube_F(test::kCubeFaces, 1 - lambda);
  std::vector<Eigen::Triplet<float, std::int32_t>> t;
  for (int i = 0; i < 6; ++i)
    for (SparseF::InnerIterator it(cube, i); it; ++it) t.emplace_back(i, std::int32_t(it.col()), it.value());
  for (int i = 0; i < 6; ++i) {
    if (lambda > 0) t.emplace_back(i, 6, float(lambda));
    if (lambda > 0) t.emplace_back(6, i, float(lambda / 100));
  }
  c.F = SparseF(7, 7);
  c.F.setFromTriplets(t.begin(), t.end());
  c.input.area = {1, 1, 1, 1, 1, 1, 100};
  for (int i = 0; i < 6; ++i) c.input.surface.push_back(SurfaceCondition{0.8, false, 0, i == 0 ? q0 : 0.0});
  c.input.surface.push_back(SurfaceCondition{1.0, true, 300, 0});
  c.input.sky = {0, 0, 0, 0, 0, 0, 1 - 6 * lambda / 100};
  return c;
}

// The defect of a stored row sum: each of the 6 entries (values <= 1) rounded to float with relative error
// <= 2^-24, and the cube's closed forms summing to 1 within 1e-9 (support/reference_problems.h).
constexpr double kRowRounding = 6.0 / (1 << 24) + 1e-9;

}  // namespace

TEST_CASE("closed cavities: a re-radiating cube that sees only itself is one, whatever is outside",
          "[exchange][cavity]") {
  const LeakyCube c = leaky_cube(0.0);
  const std::vector<ClosedCavity> k = closed_cavities(c.F, c.input);
  REQUIRE(k.size() == 1);
  CHECK(k[0].patches == std::vector<std::size_t>{0, 1, 2, 3, 4, 5});
  CHECK(k[0].area == 6.0);
  CHECK(k[0].leak <= kRowRounding);
  CHECK(k[0].given_Q == 0.0);
  // Given fluxes that do not sum to 0 inside it: still a cavity (no radiative solution at all), their sum
  // stated.
  const LeakyCube heated = leaky_cube(0.0, 10.0);
  const std::vector<ClosedCavity> h = closed_cavities(heated.F, heated.input);
  REQUIRE(h.size() == 1);
  CHECK(h[0].given_Q == 10.0);
  // A known temperature on one face fixes the level: no cavity.
  LeakyCube fixed = leaky_cube(0.0);
  fixed.input.surface[2] = SurfaceCondition{0.8, true, 320, 0};
  CHECK(closed_cavities(fixed.F, fixed.input).empty());
}

TEST_CASE(
    "closed cavities: a cube with an opening is a cavity only below the leak threshold, and solved above it",
    "[exchange][cavity]") {
  // Below the threshold: a cavity, its leak fraction measured (the opening's lambda, within the row
  // rounding).
  for (const double lambda : {1e-7, 1e-6, 0.5 * kCavityLeak}) {
    const LeakyCube c = leaky_cube(lambda);
    const std::vector<ClosedCavity> k = closed_cavities(c.F, c.input);
    INFO("lambda " << lambda);
    REQUIRE(k.size() == 1);
    CHECK(k[0].patches.size() == 6);
    CHECK(std::abs(k[0].leak - lambda) <= kRowRounding + 1e-7 * lambda);
  }
  // Above it: determined. With q = 0 every face's J is the mean of what it sees, so the uniform J = sigma
  // 300^4 of the black surface solves the block: T = 300 K. The stored rows' rounding (a defect delta <=
  // kRowRounding of each row sum, a leak to 0 K or a gain) moves J by at most delta / lambda relative (the
  // block's smallest eigenvalue is lambda), T by a quarter of that.
  for (const double lambda : {2 * kCavityLeak, 1e-2, 0.3}) {
    const LeakyCube c = leaky_cube(lambda);
    INFO("lambda " << lambda);
    CHECK(closed_cavities(c.F, c.input).empty());
    const std::vector<double> J = dense_net_radiation(c.input, c.F);
    const NetRadiationResult r = net_radiation_result(c.input, c.F, J);
    const double tolerance = 300 * (kRowRounding / lambda) / 4 + 300 * 1e-12;
    for (int i = 0; i < 6; ++i) CHECK(std::abs(r.T[std::size_t(i)] - 300) <= tolerance);
  }
}

TEST_CASE("closed cavities: known-flux patches joined to a known temperature through others are not one",
          "[exchange][cavity]") {
  // A chain 0 - 1 - 2 of re-radiating patches, 2 also seeing the black patch 3 at 290 K (reciprocal, unit
  // areas): one component with a leak of 0.5 / 3, not a cavity; the same chain with the link 2 - 3 cut is
  // one.
  for (const bool linked : {true, false}) {
    std::vector<Eigen::Triplet<float, std::int32_t>> t = {
        {0, 1, 1.0f}, {1, 0, 0.5f}, {1, 2, 0.5f}, {2, 1, 0.5f}};
    t.emplace_back(2, linked ? 3 : 2, 0.5f);  // cut: patch 2 sees itself (a concave patch)
    if (linked) t.emplace_back(3, 2, 0.5f);
    SparseF F(4, 4);
    F.setFromTriplets(t.begin(), t.end());
    NetRadiationInput in;
    in.area = {1, 1, 1, 1};
    for (int i = 0; i < 3; ++i) in.surface.push_back(SurfaceCondition{0.9, false, 0, 0});
    in.surface.push_back(SurfaceCondition{1.0, true, 290, 0});
    in.sky = {0, 0, 0, 0.5};
    const std::vector<ClosedCavity> k = closed_cavities(F, in);
    INFO("linked " << linked);
    CHECK(k.size() == (linked ? 0u : 1u));
    if (!linked) CHECK(k[0].patches == std::vector<std::size_t>{0, 1, 2});
  }
}
