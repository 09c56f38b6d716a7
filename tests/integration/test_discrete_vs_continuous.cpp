// The discrete radiosity solution (form factors by ray shooting, direct solve) against the continuous path
// tracer's patch averages, on a scene where the constant-radiosity assumption costs nothing, so the two must agree
// within their statistical errors alone.
//
// Parallel unit squares at distance 1, the emitter (E0 = pi, rho = 0) and the receiver (rho1 = 0.5) each split into
// 4 x 4 patches. The emitter does not reflect, so B_emitter = E0 exactly in both models, and for a receiver patch j
//   discrete:   B_j = rho1 * sum_{i in emitter} F_ji E0 = rho1 E0 F_{j -> emitter}
//   continuous: B_j = rho1 * (1/A_j) int_{A_j} E_irr(x) dx = rho1 E0 F_{j -> emitter}
// (the average irradiance of a patch lit by a uniform Lambertian emitter is E0 times the patch-to-emitter form
// factor). The difference is pure noise: the form-factor row's binomial error and the path tracer's error.
//
// The same holds for a thin panel in a closed box lit from both sides by black, non-reflecting walls that emit:
// both models now treat a face alike (one-sided: its back absorbs; two-sided: a patch per side), so per patch and
// per side (group means) they agree within noise, where a one-sided radiosity model against a two-sided path
// tracer used to mix a modelling difference into the comparison.
#include <catch2/catch.hpp>
#include <cmath>

#include "formfactor/form_factors.h"
#include "mesh/read_scene.h"
#include "patch/patching.h"
#include "pathtrace/patch_average.h"
#include "solve/problem.h"
#include "solve/solve_radiosity.h"
#include "support/box_scenes.h"
#include "support/reference_problems.h"
#include "support/stat_checks.h"
#include "visibility/embree_visibility.h"

using namespace radwalk;

namespace {

bool is_panel(const PatchSet& ps, std::size_t i) { return ps.material[i] == 3; }  // test::panel_box's panel

// Area-weighted mean of B (channel 0) over the panel patches of one side, and its standard error from B_se.
struct GroupMean {
  double mean = 0, se = 0;
};
GroupMean panel_mean(const PatchSet& ps, const Solution& s, bool back) {
  double a = 0, sum = 0, var = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (!is_panel(ps, i) || ps.is_back(i) != back) continue;
    a += ps.area[i];
    sum += ps.area[i] * s.B(Eigen::Index(i), 0);
    if (s.B_se.rows() > 0) var += std::pow(ps.area[i] * s.B_se(Eigen::Index(i), 0), 2);
  }
  return {sum / a, std::sqrt(var) / a};
}

}  // namespace

TEST_CASE("parallel squares: direct solve of estimated F agrees with path-traced patch averages",
          "[integration][statistical]") {
  const PatchSet patches = make_patches(load_scene(std::string(RADWALK_SOURCE_DIR) + "/meshes/parallel_squares.obj"),
                                        0.25);
  REQUIRE(patches.size() == 32);
  const EmbreeVisibility visibility(patches);

  FormFactorOptions fo;
  fo.rays_per_patch = 20000;
  fo.seed = 11;
  const FormFactors ff = estimate_form_factors(patches, visibility, fo);
  const std::vector<std::uint32_t> rays = ff.rays;
  SolveOptions so;
  so.solver = "direct";
  const Solution discrete = solve_radiosity(make_problem(patches, ff.F), so);
  REQUIRE(discrete.status == SolveStatus::converged);

  PatchAverageOptions po;
  po.spp = 20000;
  po.seed = 12;
  po.progress = false;
  const Solution continuous = estimate_patch_averages(patches, visibility, po);

  // One test per receiver patch (channels are identical: grey materials); family-wise alpha = 1e-3.
  const double alpha = sidak(1e-3, 16);
  const double z_crit = z_critical(alpha);
  const double rho1 = 0.5, E0 = kPi;
  int receivers = 0;
  double worst = 0;
  test::ZTable table("discrete vs continuous B", z_crit);
  for (std::size_t j = 0; j < patches.size(); ++j) {
    if (patches.E[j][0] > 0) {
      CHECK(discrete.B(j, 0) == Approx(E0));  // the emitter: exact in both models
      CHECK(continuous.B(j, 0) == Approx(E0));
      continue;
    }
    ++receivers;
    // Binomial standard error of F_{j -> emitter} (conservative for the stratified estimator), scaled to B.
    const double f = discrete.B(j, 0) / (rho1 * E0);
    const double se_ff = rho1 * E0 * std::sqrt(f * (1 - f) / rays[j]);
    const double se = std::hypot(se_ff, continuous.B_se(j, 0));
    const double z = (discrete.B(j, 0) - continuous.B(j, 0)) / se;
    worst = std::max(worst, std::abs(z));
    table.add_patch(static_cast<Eigen::Index>(j), 0,
                    "patch " + std::to_string(j) + " (form-factor se " + std::to_string(se_ff) + ")",
                    discrete.B(j, 0), se, continuous.B(j, 0));
  }
  table.check(&patches);
  CHECK(receivers == 16);
  INFO("largest |z| " << worst << " against " << z_crit);
  // The receiver's area-weighted mean is the whole-square form factor times rho1 E0 (Howell C-11).
  double mean = 0;
  for (std::size_t j = 0; j < patches.size(); ++j)
    if (patches.E[j][0] == 0) mean += continuous.B(j, 0) * patches.area[j];
  const double expected = rho1 * E0 * test::kOpposite;
  double var = 0;
  for (std::size_t j = 0; j < patches.size(); ++j)
    if (patches.E[j][0] == 0) var += std::pow(continuous.B_se(j, 0) * patches.area[j], 2);
  test::check_z("receiver's area-weighted mean", mean, std::sqrt(var), expected, z_critical(1e-3));
}

// The panel lit from both sides: the wall x = 0 emits Le = 1, the wall x = 1 Le = 0.5, the other walls are black
// and no emitter reflects, so each panel patch gets one bounce only: B_j = rho E_wall F_{j -> wall} in the
// discrete model and in the continuous one alike (no discretisation error, as in test_discrete_vs_continuous.cpp).
// The front faces the wall x = 0, the back the wall x = 1.
TEST_CASE("thin two-sided panel in a closed box: both sides lit, direct solve and path tracer agree per side",
          "[integration][two-sided][statistical]") {
  const double rho = 0.6;
  for (const bool two : {true, false}) {
    const PatchSet ps =
        test::panel_box(2, 3, test::diffuse_material("black", 0), test::diffuse_material("low", 0, 1.0), test::diffuse_material("high", 0, 0.5), test::diffuse_material("panel", rho),
                  two);
    const EmbreeVisibility vis(ps);
    FormFactorOptions fo;
    fo.rays_per_patch = 20000;
    fo.seed = 31;
    const FormFactors ff = estimate_form_factors(ps, vis, fo);
    SolveOptions so;
    so.solver = "direct";
    const Solution direct = solve_radiosity(make_problem(ps, ff.F), so);
    REQUIRE(direct.status == SolveStatus::converged);
    PatchAverageOptions po;
    po.spp = 20000;
    po.seed = 32;
    po.progress = false;
    const Solution pt = estimate_patch_averages(ps, vis, po);

    std::size_t panel = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) panel += is_panel(ps, i);
    REQUIRE(panel == (two ? 18u : 9u));
    // Per panel patch one two-sample test, one per side for the group means, one for the symmetry.
    test::ZTable table(std::string("panel, ") + (two ? "two" : "one") + "-sided: direct vs path tracer",
                       z_critical(sidak(1e-3, panel + 3)));
    for (std::size_t j = 0; j < ps.size(); ++j) {
      if (!is_panel(ps, j)) continue;
      const auto J = Eigen::Index(j);
      const double E_wall = kPi * (ps.is_back(j) ? 0.5 : 1.0);
      const double f = direct.B(J, 0) / (rho * E_wall);  // F_{j -> wall}, the only non-zero term
      const double se_ff = rho * E_wall * std::sqrt(f * (1 - f) / ff.rays[j]);
      table.add_patch(J, 0, "patch " + std::to_string(j) + (ps.is_back(j) ? " (back)" : " (front)"),
                      direct.B(J, 0), std::hypot(se_ff, pt.B_se(J, 0)), pt.B(J, 0));
      CHECK(direct.B(J, 0) > 0.05);  // lit, on either side
    }
    for (const bool back : {false, true}) {
      if (back && !two) continue;
      const GroupMean d = panel_mean(ps, direct, back), c = panel_mean(ps, pt, back);
      // The direct solve's group-mean error from the rows' binomial errors (rows are independent).
      double var = 0, a = 0;
      for (std::size_t j = 0; j < ps.size(); ++j) {
        if (!is_panel(ps, j) || ps.is_back(j) != back) continue;
        const double E_wall = kPi * (back ? 0.5 : 1.0), f = direct.B(Eigen::Index(j), 0) / (rho * E_wall);
        var += std::pow(ps.area[j] * rho * E_wall, 2) * f * (1 - f) / ff.rays[j];
        a += ps.area[j];
      }
      const std::string side = back ? "back" : "front";
      table.add("group mean, " + side, d.mean, std::hypot(std::sqrt(var) / a, c.se), c.mean);
    }
    if (two) {
      // By symmetry F_{front -> wall x=0} = F_{back -> wall x=1}, and the back's wall emits half: each side has
      // its own B, back = front / 2, in the path tracer (an independent check of both sides).
      const GroupMean f = panel_mean(ps, pt, false), b = panel_mean(ps, pt, true);
      table.add("path tracer: back mean = front mean / 2", b.mean, std::hypot(b.se, 0.5 * f.se), 0.5 * f.mean);
    }
    table.check(&ps);
  }
}

