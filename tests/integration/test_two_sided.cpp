// One- and two-sided surfaces (patch/patch_set.h, "Sides"; docs/two-sided.md) in every
// solver: the MTL statement, back patches, reciprocity across sides, and a thin panel in a closed box lit from
// both sides (a furnace), where the direct solve, the ray-kernel walks, the path tracer and the light tracer must
// agree per side; a one-sided back is black to the camera. The direct solve against the path tracer per side is in
// test_discrete_vs_continuous.cpp. Every Monte Carlo check is a z-test at family-wise alpha = 1e-3 per TEST_CASE, Sidak-corrected over its
// checks (docs/ARCHITECTURE.md, convention 7).
#include <catch2/catch.hpp>
#include <cmath>

#include "core/error.h"
#include "formfactor/form_factors.h"
#include "mesh/mtl.h"
#include "patch/patch_builder.h"
#include "pathtrace/camera.h"
#include "pathtrace/light_tracer.h"
#include "pathtrace/patch_average.h"
#include "pathtrace/render.h"
#include "solve/problem.h"
#include "solve/solve_radiosity.h"
#include "support/box_scenes.h"
#include "support/stat_checks.h"
#include "visibility/brute_force_visibility.h"
#include "visibility/embree_visibility.h"
#include "walk/random_walk_solver.h"

using namespace radwalk;

namespace {

constexpr double kAlpha = 1e-3;

double entry(const SparseF& F, Eigen::Index i, Eigen::Index j) { return double(F.coeff(i, j)); }

bool is_panel(const PatchSet& ps, std::size_t i) { return ps.material[i] == 3; }

}  // namespace

TEST_CASE("radwalk_two_sided in MTL: read as 0 or 1, anything else refused", "[mesh][two-sided]") {
  const auto entries = scan_mtl_text("t.mtl",
                                     "newmtl a\nKd 0.5\nradwalk_two_sided 1\n"
                                     "newmtl b\nradwalk_two_sided 0\n"
                                     "newmtl c\nKd 0.2\n");
  REQUIRE(entries.size() == 3);
  CHECK(material_from_mtl(entries[0]).two_sided);
  CHECK_FALSE(material_from_mtl(entries[1]).two_sided);
  CHECK_FALSE(material_from_mtl(entries[2]).two_sided);  // the default: one-sided
  for (const char* bad : {"radwalk_two_sided 2", "radwalk_two_sided", "radwalk_two_sided yes", "radwalk_two_sided 1 1"}) {
    INFO(bad);
    CHECK_THROWS_AS(scan_mtl_text("t.mtl", std::string("newmtl a\n") + bad + "\n"), InputError);
  }
  CHECK_THROWS_WITH(scan_mtl_text("t.mtl", "newmtl a\nradwalk_two_sided 3\n"),
                    Catch::Contains("t.mtl:2") && Catch::Contains("radwalk_two_sided needs 0 or 1"));
}

TEST_CASE("add_back_sides: a reversed patch per two-sided face, after all others", "[patch][two-sided]") {
  PatchBuilder b;
  Material two = test::diffuse_material("two", 0.5, 1.0), one = test::diffuse_material("one", 0.3), glass = test::diffuse_material("glass", 0);
  two.two_sided = true;
  glass.two_sided = true;
  glass.kind = BsdfKind::dielectric;
  const int m2 = b.add_material(two), m1 = b.add_material(one), mg = b.add_material(glass);
  b.add_quad(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 2, 0), Vec3(0, 2, 0), m2);
  b.add_quad(Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1), m1);
  b.add_triangle(Vec3(0, 0, 2), Vec3(1, 0, 2), Vec3(0, 1, 3), m2);
  b.add_triangle(Vec3(0, 0, 4), Vec3(1, 0, 4), Vec3(0, 1, 4), mg);
  const PatchSet one_sided = b.build();
  PatchSet ps = one_sided;
  REQUIRE(add_back_sides(ps) == 2);  // the two faces of "two"; the dielectric stays an interface
  REQUIRE(ps.size() == 6);
  CHECK(ps.side == std::vector<Side>{Side::front, Side::one_sided, Side::front, Side::one_sided, Side::back,
                                     Side::back});
  for (const auto& [front, back] : {std::pair<std::size_t, std::size_t>{0, 4}, {2, 5}}) {
    INFO("front " << front << ", back " << back);
    CHECK(ps.face[back] == ps.face[front]);
    CHECK(ps.material[back] == ps.material[front]);
    CHECK(ps.area[back] == Approx(ps.area[front]).epsilon(1e-15));
    CHECK((ps.normal[back] + ps.normal[front]).norm() < 1e-15);
    CHECK((ps.centroid[back] - ps.centroid[front]).norm() < 1e-15);
    CHECK((ps.E[back] == ps.E[front]).all());  // Ke applies to both sides
    const auto& f = ps.corners[front];
    const auto& r = ps.corners[back];
    if (ps.is_quad(front))
      CHECK(r == std::array<std::int32_t, 4>{f[0], f[3], f[2], f[1]});  // the same diagonal c0-c2 splits both
    else
      CHECK(r == std::array<std::int32_t, 4>{f[0], f[2], f[1], -1});
  }
  // The patches that were there keep their index and geometry.
  for (std::size_t i = 0; i < one_sided.size(); ++i) CHECK(ps.corners[i] == one_sided.corners[i]);
  CHECK(add_back_sides(ps) == 0);  // idempotent
  // --two-sided: every material except the dielectric.
  PatchSet all = one_sided;
  CHECK(add_back_sides(all, true) == 3);
  PatchSet none = one_sided;
  none.materials[std::size_t(m2)].two_sided = false;
  CHECK(add_back_sides(none) == 0);
  CHECK(none.side.empty());  // no two-sided face: the PatchSet is unchanged
}

TEST_CASE("visibility: a two-sided face is hit on the side the ray arrives on, a one-sided back is a back hit",
          "[visibility][two-sided]") {
  const Material white = test::diffuse_material("white", 0.5);
  for (const bool two : {false, true}) {
    const PatchSet ps = test::panel_box(1, 1, white, white, white, white, two);
    REQUIRE(ps.size() == (two ? 8u : 7u));
    const EmbreeVisibility embree(ps);
    const BruteForceVisibility brute(ps);
    for (const Visibility* vis : {static_cast<const Visibility*>(&embree), static_cast<const Visibility*>(&brute)}) {
      Ray from_low{Vec3(0.1, 0.5, 0.5), Vec3(1, 0, 0)}, from_high{Vec3(0.9, 0.5, 0.5), Vec3(-1, 0, 0)};
      const Hit lo = vis->intersect(from_low), hi = vis->intersect(from_high);
      CHECK(lo.patch == 6);
      CHECK(lo.front);
      CHECK(lo.t == Approx(0.4));
      CHECK(hi.t == Approx(0.4));
      if (two) {
        CHECK(hi.patch == 7);  // the back patch, reached from its own front
        CHECK(hi.front);
      } else {
        CHECK(hi.patch == 6);
        CHECK_FALSE(hi.front);  // absorbed by the solvers, counted as a back hit
      }
      CHECK(vis->occluded(from_high));
    }
  }
}

TEST_CASE("two-sided panel: twice the patches, no back hits, reciprocity A_i F_ij = A_j F_ji across sides",
          "[formfactor][two-sided]") {
  const Material white = test::diffuse_material("white", 0.5);
  const PatchSet one = test::panel_box(2, 2, white, white, white, white, false);
  const PatchSet two = test::panel_box(2, 2, white, white, white, white, true);
  const std::size_t panel_faces = 4;
  REQUIRE(two.size() == one.size() + panel_faces);  // the panel's faces doubled, nothing else

  FormFactorOptions fo;
  fo.rays_per_patch = 40000;
  fo.seed = 21;
  const FormFactors ff_one = estimate_form_factors(one, EmbreeVisibility(one), fo);
  long back_hits_one = 0;
  for (std::size_t i = 0; i < one.size(); ++i) back_hits_one += ff_one.back_hits[i];
  CHECK(back_hits_one > 0);  // one-sided: the walls behind the panel see its absorbing back

  const EmbreeVisibility vis(two);
  const FormFactors ff = estimate_form_factors(two, vis, fo);
  const auto n = Eigen::Index(two.size());
  std::size_t pairs = 0;
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = i + 1; j < n; ++j) pairs += entry(ff.F, i, j) > 0 || entry(ff.F, j, i) > 0;
  // Per pair one z-test, plus one closure check per row (deterministic).
  test::ZTable table("two-sided panel reciprocity", z_critical(sidak(kAlpha, pairs)));
  for (Eigen::Index i = 0; i < n; ++i) {
    INFO("row " << i);
    CHECK(ff.back_hits[std::size_t(i)] == 0);  // closed, and every side of the panel is a patch
    CHECK(ff.escaped[std::size_t(i)] == 0);
    CHECK(std::abs(double(ff.F.row(i).sum()) - 1) <= 1e-6);
    for (Eigen::Index j = i + 1; j < n; ++j) {
      const double fij = entry(ff.F, i, j), fji = entry(ff.F, j, i);
      if (fij == 0 && fji == 0) continue;
      const double ai = two.area[std::size_t(i)], aj = two.area[std::size_t(j)];
      const double se = std::sqrt(ai * ai * fij * (1 - fij) / double(ff.rays[std::size_t(i)]) +
                                  aj * aj * fji * (1 - fji) / double(ff.rays[std::size_t(j)]));
      table.add("A F(" + std::to_string(i) + "," + std::to_string(j) + ") - A F(" + std::to_string(j) + "," +
                    std::to_string(i) + ")",
                ai * fij - aj * fji, se, 0.0);
    }
  }
  table.check();
  // A patch of the panel never sees its own other side.
  for (Eigen::Index i = 0; i < n; ++i)
    if (two.is_back(std::size_t(i))) CHECK(entry(ff.F, i, i - Eigen::Index(panel_faces)) == 0);
}

// A furnace with a thin two-sided panel: every surface, both sides of the panel included, emits E = pi and
// reflects rho = 0.5, and the box is closed, so B = E / (1 - rho) = 2 pi at every point of every side, exactly, in
// the discrete model and the continuous one alike (constant B costs no discretisation error). Every solver that
// traces rays must find it on both sides of the panel: the ray-kernel walk, the path tracer and the light tracer.
// A one-sided panel breaks the furnace: its back absorbs and emits nothing, so the walls facing it are darker.
TEST_CASE("furnace with a thin two-sided panel: B = E / (1 - rho) on both sides in every solver",
          "[integration][two-sided][statistical]") {
  const Material white = test::diffuse_material("white", 0.5, 1.0);
  const double exact = kPi / (1 - 0.5);
  const PatchSet ps = test::panel_box(2, 2, white, white, white, white, true);
  const EmbreeVisibility vis(ps);
  std::vector<int> panel;
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (is_panel(ps, i)) panel.push_back(int(i));
  REQUIRE(panel.size() == 8);

  FormFactorOptions fo;
  fo.rays_per_patch = 4000;
  fo.seed = 41;
  const FormFactors ff = estimate_form_factors(ps, vis, fo);
  SolveOptions so;
  so.solver = "direct";
  const Solution direct = solve_radiosity(make_problem(ps, ff.F), so);
  REQUIRE(direct.status == SolveStatus::converged);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    INFO("patch " << i << ", back hits " << ff.back_hits[i]);
    CHECK(ff.back_hits[i] == 0);
    CHECK(direct.B(Eigen::Index(i), 0) == Approx(exact).epsilon(1e-5));  // rows sum to 1 to float rounding
  }

  WalkOptions wo;
  wo.method = WalkMethod::gather_collision;
  wo.kernel = WalkKernel::ray;
  wo.walks_per_patch = 20000;
  wo.seed = 42;
  wo.patches = panel;
  wo.progress = false;
  const Solution walk = solve_random_walk(make_problem(ps, ff.F), &ps, &vis, wo);
  PatchAverageOptions po;
  po.spp = 20000;
  po.seed = 43;
  po.progress = false;
  const Solution pt = estimate_patch_averages(ps, vis, po);
  LightTraceOptions lo;
  lo.particles = 400000;
  lo.seed = 44;
  lo.progress = false;
  const Solution light = light_trace_patches(ps, vis, lo);

  const double alpha = sidak(kAlpha, 3 * panel.size() + 1);  // the panel rows and the one-sided check
  test::ZTable table("furnace with a two-sided panel", z_critical(alpha));
  for (const int j : panel) {
    const std::string side = ps.is_back(std::size_t(j)) ? " (back)" : " (front)";
    table.add_patch(j, 0, "ray-kernel walk, patch " + std::to_string(j) + side, walk.B(j, 0), walk.B_se(j, 0),
                    exact);
    table.add_patch(j, 0, "path tracer, patch " + std::to_string(j) + side, pt.B(j, 0), pt.B_se(j, 0), exact);
    table.add_patch(j, 0, "light tracer, patch " + std::to_string(j) + side, light.B(j, 0), light.B_se(j, 0),
                    exact);
  }
  table.check(&ps);

  // One-sided panel: the walls x = 1 face its black back; their path-traced mean is below the furnace value by
  // more than its error (a one-sided z-test, one more member of the family).
  const PatchSet one = test::panel_box(2, 2, white, white, white, white, false);
  const EmbreeVisibility vis_one(one);
  po.spp = 4000;
  const Solution pt_one = estimate_patch_averages(one, vis_one, po);
  double a = 0, sum = 0, var = 0;
  for (std::size_t i = 0; i < one.size(); ++i)
    if (one.material[i] == 2) {
      a += one.area[i];
      sum += one.area[i] * pt_one.B(Eigen::Index(i), 0);
      var += std::pow(one.area[i] * pt_one.B_se(Eigen::Index(i), 0), 2);
    }
  const double z = (sum / a - exact) / (std::sqrt(var) / a);
  INFO("wall x = 1 behind a one-sided panel: mean B " << sum / a << " against " << exact << ", z " << z);
  CHECK(z < -z_critical(2 * alpha));  // one-sided at level alpha
}

// A camera between the panel and the wall x = 1, looking at the panel's back (every pixel sees it), the wall
// x = 1 the only emitter. One-sided: the back is black, exactly, for the path tracer and the light tracer.
// Two-sided: the back patch is lit, and the image shows it.
TEST_CASE("a camera looking at a face's back sees black where it is one-sided", "[pathtrace][two-sided]") {
  Camera camera;
  camera.position = Vec3(0.9, 0.5, 0.5);
  camera.direction = Vec3(-1, 0, 0);
  camera.up = Vec3(0, 0, 1);
  camera.vfov = 20 * kPi / 180;  // at distance 0.4 the view is 0.14 wide, inside the panel's 0.5
  RenderOptions ro;
  ro.width = 16;
  ro.height = 16;
  ro.spp = 64;
  ro.seed = 51;
  ro.progress = false;
  LightTraceOptions lo;
  lo.particles = 200000;
  lo.seed = 52;
  lo.progress = false;
  for (const bool two : {false, true}) {
    const PatchSet ps =
        test::panel_box(1, 1, test::diffuse_material("black", 0), test::diffuse_material("low", 0), test::diffuse_material("high", 0, 1.0), test::diffuse_material("panel", 0.6), two);
    const EmbreeVisibility vis(ps);
    for (const IntegratorKind kind : {IntegratorKind::implicit, IntegratorKind::nee, IntegratorKind::mis}) {
      ro.integrator.kind = kind;
      const RenderResult image = render_image(ps, vis, camera, ro);
      INFO((two ? "two" : "one") << "-sided, integrator " << to_string(kind));
      if (!two) {
        for (const Rgb& p : image.mean.pixels) CHECK((p == 0).all());
      } else {
        // Every pixel sees the lit back: each pixel's mean is positive by more than z_crit standard errors.
        const double zc = z_critical(sidak(kAlpha, 3 * image.mean.pixels.size()));
        int dark = 0;
        for (std::size_t k = 0; k < image.mean.pixels.size(); ++k)
          dark += !(image.mean.pixels[k][0] > zc * image.se.pixels[k][0]);
        CHECK(dark == 0);
      }
    }
    const RenderResult traced = light_trace_image(ps, vis, camera, 16, 16, lo);
    if (!two) {
      INFO("light tracer, one-sided");
      for (const Rgb& p : traced.mean.pixels) CHECK((p == 0).all());
    } else {
      INFO("light tracer, two-sided: mean " << traced.mean.mean()[0]);
      CHECK(traced.mean.mean()[0] > 0);
    }
  }
}
