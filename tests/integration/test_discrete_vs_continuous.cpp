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
#include <catch2/catch.hpp>
#include <cmath>

#include "formfactor/form_factors.h"
#include "mesh/read_scene.h"
#include "patch/patching.h"
#include "pathtrace/patch_average.h"
#include "solve/problem.h"
#include "solve/solve_radiosity.h"
#include "support/reference_problems.h"
#include "support/stat_checks.h"
#include "visibility/embree_visibility.h"

using namespace radwalk;

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
