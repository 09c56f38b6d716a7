// The ray kernel (no stored F) agrees with the exact solution on the unit cube, whose exact form factors are
// known: every method's estimate passes a z-test against the dense solve with the analytic F (family-wise
// alpha = 1e-3, Sidak over scenes x methods x patches x channels); the form-factor error of the analytic F stored
// in float (1e-8) is far below the Monte Carlo error. Closed cube and an open cube (one face missing: escapes).
#include <catch2/catch.hpp>

#include "core/stats.h"
#include "visibility/brute_force_visibility.h"
#include "walk/random_walk_solver.h"
#include "walk/walk_variance.h"
#include "walk_test_checks.h"
#include "walk_test_scenes.h"

using namespace radwalk;

TEST_CASE("ray kernel agrees with the exact solution of the cube", "[walk][ray]") {
  const std::vector<std::vector<int>> face_sets = {{0, 1, 2, 3, 4, 5}, {0, 1, 2, 3, 4}};
  const double z_crit = z_critical(sidak(1e-3, 2 * walk_methods().size() * 6 * 3));
  int rejected = 0;
  for (const auto& faces : face_sets) {
    const RadiosityProblem p = test::mixed_cube(faces);
    const PatchSet patches = test::cube_patches(p, faces);
    for (std::size_t k = 0; k < patches.size(); ++k) CHECK(patches.normal[k].dot(Vec3(0.5, 0.5, 0.5) - patches.centroid[k]) > 0);
    const BruteForceVisibility visibility(patches);
    const PatchRgb B = dense_radiosity(p);
    RadiosityProblem no_F = p;
    no_F.F = SparseF();  // the ray kernel must not need F
    for (const std::string& method : walk_methods()) {
      WalkOptions o;
      set_method(o, method);
      o.kernel = "ray";
      o.walks = o.walk == "gather" ? 20000 : 120000;
      o.seed = 3;
      const Solution s = solve_random_walk(no_F, &patches, &visibility, o);
      rejected += test::count_rejections(s, B, z_crit, std::to_string(faces.size()) + " faces, ray " + method);
      CHECK(s.info.at("back_hits") == 0);
      if (faces.size() == 6) CHECK(s.info.at("escapes") == 0);  // watertight: no ray leaks
      if (faces.size() == 5) CHECK(s.info.at("escapes") > 0);
      CHECK(std::isnan(s.info.at("variance_radius")));
    }
  }
  CHECK(rejected == 0);
}

TEST_CASE("ray kernel counts back-face hits and ends the walk there", "[walk][ray]") {
  // Face 5 turned around (normal outwards): rays from inside that reach it hit its back.
  RadiosityProblem p = test::mixed_cube();
  PatchSet patches = test::cube_patches(p);
  auto& c = patches.corners[5];
  std::swap(c[1], c[3]);
  compute_patch_geometry(patches);
  const BruteForceVisibility visibility(patches);
  WalkOptions o;
  o.kernel = "ray";
  o.estimator = "collision";
  o.walks = 2000;
  o.patches = {0, 1, 2, 3, 4};  // walks from face 5 itself would leave through its (outward) front
  const Solution s = solve_random_walk(p, &patches, &visibility, o);
  CHECK(s.info.at("back_hits") > 0);
  CHECK(s.info.at("escapes") == 0);
}
