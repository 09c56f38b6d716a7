// The errors of group means (solve/group_mean_error.h) against their definitions computed densely: on the unit
// cube room (6 patches, the ceiling emitting) with F_ij = 0.2 (i != j), rho = 0.5 and given sources d and their
// standard deviations, the adjoint Psi_g = (I - H)^{-T} (A 1_g) by a dense LU solve gives
//   eps_g = sum_c sum_j Psi_gjc d_jc,  Var = (sum_c sqrt(sum_j Psi_gjc^2 sd_jc^2))^2,  M_g = sum_{i in g} A_i sum_c B_ic,
// and the shares |sum_c Psi_gjc d_jc| / M_g; with a noise model (gather standard errors G, the solver's own s) the
// first-order statistical part sqrt((sum_c sqrt(sum_j (Psi_gjc rho_jc G_jc)^2))^2 + (sum_{i in g} A_i sum_c
// s_ic)^2) / M_g, without one the bound sum_{i in g} A_i sum_c B_se_ic / M_g. Deterministic: exact up to the
// adjoint's sweeps (relative change below 1e-10).
#include <catch2/catch.hpp>

#include <cmath>

#include <Eigen/Dense>

#include "core/error.h"
#include "patch/patch_grouping.h"
#include "solve/group_mean_error.h"
#include "solve/problem.h"
#include "support/box_scenes.h"

using namespace radwalk;

namespace {

// The 6-patch room above with its F, B, B_se, d, sd, gather standard errors G and a solver's own error s.
struct SmallRoom {
  PatchSet p;
  SparseF F;
  PatchRgb B, B_se, d, sd, G, own;
};

SmallRoom small_room() {
  SmallRoom r;
  PatchSet& p = r.p;
  p = test::unit_cube_room(1);
  const std::size_t N = p.size();
  p.materials.resize(3);
  p.materials[0].name = "walls";
  p.materials[1].name = "floor";
  p.materials[2].name = "light";
  for (std::size_t i = 0; i < N; ++i) {
    const double z = p.centroid[i].z();
    p.material[i] = z > 1 - 1e-9 ? 2 : z < 1e-9 ? 1 : 0;
    p.rho[i] = Rgb(0.5, 0.4, 0.3);
    p.E[i] = z > 1 - 1e-9 ? Rgb(1, 1, 1) : Rgb(0, 0, 0);
  }
  std::vector<Eigen::Triplet<float>> t;
  for (std::size_t i = 0; i < N; ++i)
    for (std::size_t j = 0; j < N; ++j)
      if (i != j) t.emplace_back(int(i), int(j), 0.2f);
  r.F = SparseF{static_cast<Eigen::Index>(N), static_cast<Eigen::Index>(N)};
  r.F.setFromTriplets(t.begin(), t.end());
  const auto n = Eigen::Index(N);
  r.B.resize(n, 3), r.B_se.resize(n, 3), r.d.resize(n, 3), r.sd.resize(n, 3), r.G.resize(n, 3), r.own.resize(n, 3);
  for (Eigen::Index i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      r.B(i, c) = 0.3 + 0.1 * double(i) + 0.05 * c;
      r.B_se(i, c) = 0.01 * (1 + c);
      r.d(i, c) = 0.02 * std::sin(double(3 * i + c + 1));
      r.sd(i, c) = 0.005 * (1 + double(i % 3));
      r.G(i, c) = 0.004 * (1 + double((i + c) % 4));
      r.own(i, c) = 0.002 * (1 + double(i % 2));
    }
  return r;
}

// The adjoint Psi_g of channel c by a dense LU solve, and W = A 1_g over the counted patches.
Eigen::VectorXd dense_adjoint(const SmallRoom& r, const RadiosityProblem& problem, const PatchGrouping& grouping,
                              std::size_t g, int c, Eigen::VectorXd& W) {
  const auto n = Eigen::Index(r.p.size());
  Eigen::MatrixXd IH = Eigen::MatrixXd::Identity(n, n);
  W = Eigen::VectorXd::Zero(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) IH(i, j) -= problem.rho(i, c) * double(r.F.coeff(i, j));
    if (grouping.group[std::size_t(i)] == std::int32_t(g) && r.p.E[std::size_t(i)].maxCoeff() <= 0)
      W[i] = r.p.area[std::size_t(i)];
  }
  return IH.transpose().partialPivLu().solve(W);
}

}  // namespace

TEST_CASE("group mean errors: the adjoint-weighted source summed over a group, as a dense solve gives it") {
  const SmallRoom r = small_room();
  const PatchSet& p = r.p;
  const std::size_t N = p.size();
  const RadiosityProblem problem = make_problem(p, r.F);
  const PatchRgb &B = r.B, &B_se = r.B_se, &d = r.d, &sd = r.sd;
  const PatchGrouping grouping = group_patches(p, "material");
  const std::vector<GroupMeanError> groups = group_mean_errors(p, grouping, problem, B, B_se, d, sd, 0.0);
  REQUIRE(groups.size() == 3);
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const GroupMeanError& x = groups[g];
    if (x.name == "light") {  // only an emitter: nothing counted
      CHECK_FALSE(x.counted);
      continue;
    }
    REQUIRE(x.counted);
    double M = 0, se = 0, eps = 0, sd_sum = 0, area = 0;
    std::vector<double> share(N, 0.0);
    for (int c = 0; c < 3; ++c) {
      Eigen::VectorXd W;
      const Eigen::VectorXd psi = dense_adjoint(r, problem, grouping, g, c, W);
      double var = 0;
      for (Eigen::Index j = 0; j < Eigen::Index(N); ++j) {
        eps += psi[j] * d(j, c);
        var += psi[j] * psi[j] * sd(j, c) * sd(j, c);
        share[std::size_t(j)] += psi[j] * d(j, c);
        if (W[j] > 0) M += W[j] * B(j, c), se += W[j] * B_se(j, c);
      }
      sd_sum += std::sqrt(var);
    }
    for (std::size_t i = 0; i < N; ++i)
      if (grouping.group[i] == std::int32_t(g)) area += p.area[i];
    CHECK(x.area == Approx(area));
    CHECK(x.mean == Approx(M / (3 * area)).epsilon(1e-12));
    CHECK(x.estimate == Approx(eps / M).epsilon(1e-8));
    CHECK(x.discretisation == Approx(std::hypot(eps, sd_sum) / M).epsilon(1e-8));
    CHECK(x.statistical == Approx(se / M).epsilon(1e-12));
    CHECK(x.statistical_bound == Approx(se / M).epsilon(1e-12));
    CHECK(x.statistical_kind == "bound");
    CHECK(x.total == Approx(std::hypot(x.discretisation, x.statistical)).epsilon(1e-12));
    REQUIRE(x.share.size() == N);
    for (std::size_t j = 0; j < N; ++j) CHECK(x.share[j] == Approx(std::abs(share[j]) / M).epsilon(1e-8).margin(1e-14));
  }
  // Shares are kept only above the threshold.
  const std::vector<GroupMeanError> none = group_mean_errors(p, grouping, problem, B, B_se, d, sd);
  for (const GroupMeanError& x : none) CHECK(x.share.empty());
}

TEST_CASE("group mean errors: the first-order statistical part is the adjoint-weighted row noise as a dense solve gives it") {
  const SmallRoom r = small_room();
  const RadiosityProblem problem = make_problem(r.p, r.F);
  const PatchGrouping grouping = group_patches(r.p, "material");
  const std::size_t N = r.p.size();
  for (const bool walks : {false, true}) {
    DYNAMIC_SECTION((walks ? "with a solver's own error" : "a deterministic solver")) {
      GroupNoiseModel noise;
      noise.gather_standard_error = r.G;
      if (walks) noise.solver_standard_error = r.own;
      const std::vector<GroupMeanError> groups =
          group_mean_errors(r.p, grouping, problem, r.B, r.B_se, r.d, r.sd, HUGE_VAL, noise);
      const std::vector<GroupMeanError> bound = group_mean_errors(r.p, grouping, problem, r.B, r.B_se, r.d, r.sd);
      REQUIRE(groups.size() == 3);
      for (std::size_t g = 0; g < groups.size(); ++g) {
        const GroupMeanError& x = groups[g];
        if (!x.counted) continue;
        double M = 0, from_F = 0, own = 0, se = 0;
        for (int c = 0; c < 3; ++c) {
          Eigen::VectorXd W;
          const Eigen::VectorXd psi = dense_adjoint(r, problem, grouping, g, c, W);
          double var = 0;
          for (Eigen::Index j = 0; j < Eigen::Index(N); ++j) {
            const double a = psi[j] * problem.rho(j, c) * r.G(j, c);
            var += a * a;
            if (W[j] > 0) M += W[j] * r.B(j, c), own += W[j] * r.own(j, c), se += W[j] * r.B_se(j, c);
          }
          from_F += std::sqrt(var);  // the channels as if fully correlated
        }
        INFO(x.name);
        CHECK(x.statistical_kind == (walks ? "first-order+walk-bound" : "first-order"));
        CHECK(x.statistical == Approx(std::hypot(from_F, walks ? own : 0.0) / M).epsilon(1e-8));
        CHECK(x.statistical_bound == Approx(se / M).epsilon(1e-12));
        // The discretisation part does not depend on the noise model.
        CHECK(x.discretisation == Approx(bound[g].discretisation).epsilon(1e-12));
        CHECK(x.total == Approx(std::hypot(x.discretisation, x.statistical)).epsilon(1e-12));
      }
    }
  }
}

TEST_CASE("group mean errors: patches grouped by a name that is not object, group or material are refused") {
  const PatchSet p = test::unit_cube_room(1);
  CHECK_THROWS_AS(group_patches(p, "colour"), InputError);
  const PatchGrouping g = group_patches(p, "object");
  CHECK(g.names.size() == 1);  // no names: all "(none)"
  CHECK(g.names[0] == "(none)");
}
