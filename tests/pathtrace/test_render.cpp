// Images: a camera inside the furnace sees L = Le / (1 - rho) everywhere; reproducibility; the Cornell box.
#include <catch2/catch.hpp>
#include <filesystem>

#include "core/parallel.h"
#include "pathtrace/light_tracer.h"
#include "io/png_writer.h"
#include "pathtrace/render.h"
#include "scenes.h"
#include "support/stat_checks.h"
#include "visibility/brute_force_visibility.h"

using namespace radwalk;

namespace {
PatchSet furnace_scene(const Rgb& rho, const Rgb& Le) {
  PatchBuilder b;
  const int m = b.add_material("furnace", rho, Le);
  return test::closed_box(Vec3(1, 1, 1), 2, b, [&](int, int, int) { return m; });
}
}  // namespace

TEST_CASE("render: inside the furnace every pixel has mean L = Le / (1 - rho)", "[render][statistical]") {
  // H0: the image mean (24 x 16 pixels x 32 spp, independent samples) equals Le / (1 - rho), per channel and
  // integrator: 9 checks, alpha = 1e-3 family-wise. se of the image mean = sqrt(sum se_p^2) / pixels.
  const Rgb rho(0.3, 0.5, 0.7), Le(1.0, 2.0, 0.5);
  const PatchSet p = furnace_scene(rho, Le);
  const BruteForceVisibility vis(p);
  const Camera cam{Vec3(0.5, 0.4, 0.1), Vec3(0.1, 0.2, 1), Vec3(0, 1, 0), 1.2};
  const double z = z_critical(sidak(1e-3, 9));
  for (IntegratorKind kind : {IntegratorKind::implicit, IntegratorKind::nee, IntegratorKind::mis}) {
    RenderOptions o;
    o.width = 24;
    o.height = 16;
    o.spp = 32;
    o.seed = 301;
    o.integrator.kind = kind;
    o.progress = false;
    const RenderResult r = render_image(p, vis, cam, o);
    CHECK(r.rays > 24 * 16 * 32);
    for (int c = 0; c < 3; ++c) {
      double mean = 0, var = 0;
      for (std::size_t k = 0; k < r.mean.pixels.size(); ++k) {
        mean += r.mean.pixels[k][c];
        var += r.se.pixels[k][c] * r.se.pixels[k][c];
      }
      const double n = static_cast<double>(r.mean.pixels.size());
      INFO(to_string(kind) << " channel " << c);
      test::check_z("furnace image mean", mean / n, std::sqrt(var) / n, Le[c] / (1 - rho[c]), z);
    }
  }
}

TEST_CASE("render is bit-identical for 1 and 2 threads", "[render]") {
  const PatchSet p = furnace_scene(Rgb::Constant(0.5), Rgb::Constant(1.0));
  const BruteForceVisibility vis(p);
  RenderOptions o;
  o.width = 12;
  o.height = 10;
  o.spp = 8;
  o.progress = false;
  const Camera cam{Vec3(0.5, 0.5, 0.1), Vec3(0, 0, 1), Vec3(0, 1, 0), 1.0};
  RenderResult one, two;
  {
    const ThreadLimit limit(1);
    one = render_image(p, vis, cam, o);
  }
  {
    const ThreadLimit limit(2);
    two = render_image(p, vis, cam, o);
  }
  for (std::size_t k = 0; k < one.mean.pixels.size(); ++k) CHECK((one.mean.pixels[k] == two.mean.pixels[k]).all());
  CHECK(one.rays == two.rays);
}

TEST_CASE("light-traced images: furnace mean and agreement with the path-traced image", "[render][lighttrace][statistical]") {
  // H0 1: inside the furnace the image mean is Le / (1 - rho) (3 channels). H0 2: on a lit room (lamp in the
  // ceiling, an obstacle) the light-traced and path-traced images have equal means over each of 4 quadrants
  // (4 x 3 two-sample z-tests). 15 checks, alpha = 1e-3 family-wise. Pixel errors of the light-traced image are
  // correlated (one particle splats to many pixels), so quadrant se's add the pixel se's linearly (an upper
  // bound); the path-traced pixels are independent.
  const double z = z_critical(sidak(1e-3, 15));
  LightTraceOptions lo;
  lo.progress = false;
  lo.particles = 200000;
  lo.seed = 302;
  {
    const Rgb rho(0.3, 0.5, 0.7), Le(1.0, 2.0, 0.5);
    const PatchSet p = furnace_scene(rho, Le);
    const BruteForceVisibility vis(p);
    const Camera cam{Vec3(0.5, 0.4, 0.1), Vec3(0.1, 0.2, 1), Vec3(0, 1, 0), 1.2};
    const RenderResult r = light_trace_image(p, vis, cam, 12, 8, lo);
    for (int c = 0; c < 3; ++c) {
      double mean = 0, se = 0;
      for (std::size_t k = 0; k < r.mean.pixels.size(); ++k) {
        mean += r.mean.pixels[k][c];
        se += r.se.pixels[k][c];
      }
      const double n = static_cast<double>(r.mean.pixels.size());
      test::check_z("light-traced furnace image mean", mean / n, se / n, Le[c] / (1 - rho[c]), z);
    }
  }
  PatchBuilder b;
  const int white = b.add_material("white", Rgb(0.725, 0.71, 0.68));
  const int red = b.add_material("red", Rgb(0.63, 0.065, 0.05));
  const int lamp = b.add_material("lamp", Rgb::Constant(0.78), Rgb(17, 12, 4));
  test::add_cube_outward(b, Vec3(0.3, 0.0001, 0.5), 0.3, white);
  const PatchSet p = test::closed_box(Vec3(1, 1, 1), 3, b, [&](int f, int a, int c) {
    if (f == 3 && a == 1 && c == 1) return lamp;
    return f == 1 ? red : white;
  });
  const BruteForceVisibility vis(p);
  const Camera cam{Vec3(0.5, 0.5, 0.02), Vec3(0, 0, 1), Vec3(0, 1, 0), 1.4};
  const RenderResult lt = light_trace_image(p, vis, cam, 16, 16, lo);
  RenderOptions o;
  o.width = o.height = 16;
  o.spp = 64;
  o.seed = 303;
  o.progress = false;
  const RenderResult pt = render_image(p, vis, cam, o);
  for (int q = 0; q < 4; ++q)
    for (int c = 0; c < 3; ++c) {
      double a = 0, sa = 0, m = 0, vm = 0;
      for (int y = (q / 2) * 8; y < (q / 2) * 8 + 8; ++y)
        for (int x = (q % 2) * 8; x < (q % 2) * 8 + 8; ++x) {
          a += lt.mean.at(x, y)[c];
          sa += lt.se.at(x, y)[c];
          m += pt.mean.at(x, y)[c];
          vm += pt.se.at(x, y)[c] * pt.se.at(x, y)[c];
        }
      const double se = std::hypot(sa, std::sqrt(vm));
      INFO("quadrant " << q << " channel " << c << ": light " << a / 64 << " +- " << sa / 64 << ", path " << m / 64
                       << " +- " << std::sqrt(vm) / 64);
      CHECK(std::abs(a - m) / se < z);
    }
}
