// The Cornell box (meshes/cornell_box.obj) through Embree: the integrators and the light tracer agree on the
// patch averages; the rendered image has the red wall on the left and the green wall on the right.
#include <catch2/catch.hpp>
#include <filesystem>

#include "mesh/read_scene.h"
#include "patch/patching.h"
#include "pathtrace/light_tracer.h"
#include "pathtrace/patch_average.h"
#include "pathtrace/render.h"
#include "support/stat_checks.h"
#include "visibility/embree_visibility.h"

using namespace radwalk;

namespace {
const std::string kCornell = std::string(RADWALK_SOURCE_DIR) + "/meshes/cornell_box.obj";

}  // namespace

TEST_CASE("Cornell box: implicit, NEE and light tracing agree with MIS on every patch", "[pathtrace][cornell][statistical]") {
  // H0: equal expectations; 3 comparisons x patches x 3 channels, two-sample z-tests, alpha = 1e-3 family-wise.
  // The light touches only the coplanar ceiling, so NEE has finite variance here.
  REQUIRE(std::filesystem::exists(kCornell));
  const PatchSet p = make_patches(load_scene(kCornell), 0);
  const EmbreeVisibility vis(p);
  CHECK(is_diffuse_scene(p));
  PatchAverageOptions o;
  o.progress = false;
  o.spp = 2000;
  o.seed = 401;
  const Solution mis = estimate_patch_averages(p, vis, o);
  o.integrator.kind = IntegratorKind::nee;
  o.seed = 402;
  const Solution nee = estimate_patch_averages(p, vis, o);
  o.integrator.kind = IntegratorKind::implicit;
  o.spp = 6000;
  o.seed = 403;
  const Solution implicit = estimate_patch_averages(p, vis, o);
  LightTraceOptions lo;
  lo.particles = 400000;
  lo.seed = 404;
  lo.progress = false;
  const Solution light = light_trace_patches(p, vis, lo);
  const double z = z_critical(sidak(1e-3, 3 * p.size() * 3));
  test::check_solutions_agree(implicit, mis, z, &p);
  test::check_solutions_agree(nee, mis, z, &p);
  test::check_solutions_agree(light, mis, z, &p);
}

TEST_CASE("Cornell box image: red wall on the left, green on the right", "[render][cornell][statistical]") {
  // H0 (to reject): the left and right image columns have the same red-minus-green radiance. One-sided
  // z-tests on the mean over a 6-pixel-wide strip at each side (rows 16..47 of 64): 2 checks, alpha = 1e-3.
  REQUIRE(std::filesystem::exists(kCornell));
  const PatchSet p = make_patches(load_scene(kCornell), 0);
  const EmbreeVisibility vis(p);
  RenderOptions o;
  o.width = o.height = 64;
  o.spp = 8;
  o.progress = false;
  const RenderResult r = render_image(p, vis, Camera::cornell_box(), o);
  const double z = z_critical(2 * sidak(1e-3, 2));  // one-sided
  auto strip = [&](int x0) {
    double d = 0, v = 0;
    int n = 0;
    for (int y = 16; y < 48; ++y)
      for (int x = x0; x < x0 + 6; ++x, ++n) {
        d += r.mean.at(x, y)[0] - r.mean.at(x, y)[1];
        v += r.se.at(x, y)[0] * r.se.at(x, y)[0] + r.se.at(x, y)[1] * r.se.at(x, y)[1];  // conservative (no cov)
      }
    return std::pair{d / n, std::sqrt(v) / n};
  };
  const auto [left, left_se] = strip(1);
  const auto [right, right_se] = strip(57);
  INFO("left red-green " << left << " +- " << left_se << ", right " << right << " +- " << right_se);
  CHECK(left > z * left_se);
  CHECK(-right > z * right_se);
}
