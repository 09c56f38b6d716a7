// The camera response (pathtrace/camera_response.h): M = <R, B>_A is the image's mean pixel radiance, checked
// against the path tracer's image of the same view where the discrete and the continuous models agree exactly
// (every face an emitter of its own radiance, nothing reflects: B = E pointwise).
#include <catch2/catch.hpp>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"
#include "pathtrace/camera_response.h"
#include "pathtrace/render.h"
#include "patch/patch_builder.h"
#include "solve/measurement.h"
#include "support/stat_checks.h"
#include "visibility/embree_visibility.h"

using namespace radwalk;

namespace {

// The unit cube seen from inside, each face split into 2 x 2 quads (inward normals), patch k emitting
// Le = 1 + k / 4 per channel (channel c scaled by 1 + c / 2), rho = 0.
PatchSet emitting_cube() {
  PatchBuilder b;
  const Vec3 centre(0.5, 0.5, 0.5);
  int k = 0;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side)
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) {
          const int u = (axis + 1) % 3, v = (axis + 2) % 3;
          std::vector<Vec3> q(4, Vec3::Zero());
          const double uv[4][2] = {{0, 0}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}};
          for (int c = 0; c < 4; ++c) {
            q[c](axis) = side;
            q[c](u) = 0.5 * i + uv[c][0];
            q[c](v) = 0.5 * j + uv[c][1];
          }
          if ((q[1] - q[0]).cross(q[2] - q[0]).dot(centre - q[0]) < 0) std::swap(q[1], q[3]);
          const double L = 1 + k / 4.0;
          const int m = b.add_material("m" + std::to_string(k), Rgb::Zero(), Rgb(L, 1.5 * L, 2 * L));
          b.add_quad(q[0], q[1], q[2], q[3], m);
          ++k;
        }
  return b.build();
}

}  // namespace

TEST_CASE("camera response: M = <R, B>_A is the path tracer's mean pixel radiance of the same view",
          "[camera_response][statistical]") {
  const PatchSet patches = emitting_cube();
  const EmbreeVisibility visibility(patches);
  // Inside the cube, looking into a corner region: many patches and edges in view.
  Camera cam;
  cam.position = Vec3(0.3, 0.4, 0.35);
  cam.direction = Vec3(0.6, 0.5, 0.8).normalized();
  cam.up = Vec3(0, 1, 0);
  cam.vfov = 70.0 * kPi / 180.0;
  const int W = 96, H = 80, n = 32;
  const PinholeCamera camera(cam, W, H);
  const CameraResponse response = camera_response(camera, visibility, patches, n);
  REQUIRE(response.pixels == W * H);
  CHECK(response.fraction.sum() == Approx(1.0).epsilon(1e-12));  // inside a closed box every ray hits a front
  int seen = 0;
  for (Eigen::Index i = 0; i < response.fraction.size(); ++i) seen += response.fraction(i) > 0;
  REQUIRE(seen >= 8);  // a non-trivial view
  PatchRgb B(static_cast<Eigen::Index>(patches.size()), 3);
  for (std::size_t i = 0; i < patches.size(); ++i) B.row(Eigen::Index(i)) = patches.E[i].transpose();
  Eigen::VectorXd area(static_cast<Eigen::Index>(patches.size()));
  for (std::size_t i = 0; i < patches.size(); ++i) area(Eigen::Index(i)) = patches.area[i];
  const Rgb M = measure(area, response.R, B);

  RenderOptions ro;
  ro.width = W;
  ro.height = H;
  ro.spp = 64;
  ro.seed = 4;
  ro.progress = false;
  const RenderResult image = render_image(patches, visibility, cam, ro);
  // Mean pixel value and its standard error (pixels are independent).
  Rgb mean = Rgb::Zero(), var = Rgb::Zero();
  for (std::size_t p = 0; p < image.mean.pixels.size(); ++p) {
    mean += image.mean.pixels[p];
    var += image.se.pixels[p].square();
  }
  const double P = double(W) * H;
  mean /= P;
  const Rgb se = var.sqrt() / P;
  // Quadrature bound of the response: a pixel crossed by k edge lines has at most k (2n - 1) of its n^2 points
  // on the wrong side (a line crosses at most 2n - 1 cells of an n x n grid); k <= 3 (a cube corner), so its
  // fraction is off by at most 3 (2n - 1) / n^2, and M by that times the spread of B / pi, per boundary pixel.
  Rgb Emax = Rgb::Zero(), Emin = Rgb::Constant(1e300);
  for (const Rgb& e : patches.E) Emax = Emax.max(e), Emin = Emin.min(e);
  const double z_crit = z_critical(sidak(1e-3, 3));
  for (int c = 0; c < 3; ++c) {
    const double bound =
        double(response.boundary_pixels) / P * 3.0 * (2 * n - 1) / (n * n) * (Emax(c) - Emin(c)) / kPi;
    INFO("channel " << c << ": response M " << M(c) << ", image mean " << mean(c) << " +- " << se(c)
                    << ", quadrature bound " << bound << " (" << response.boundary_pixels << " boundary pixels)");
    CHECK(std::abs(M(c) - mean(c)) <= z_crit * se(c) + bound);
    CHECK(bound < 0.02 * M(c));  // the check is tight enough to see a wrong weighting
  }
}

TEST_CASE("camera response does not depend on the thread count", "[camera_response]") {
  const PatchSet patches = emitting_cube();
  const EmbreeVisibility visibility(patches);
  Camera cam;
  cam.position = Vec3(0.5, 0.5, 0.1);
  cam.direction = Vec3(0.1, 0.2, 1).normalized();
  const PinholeCamera camera(cam, 40, 30);
  CameraResponse one, two;
  {
    const ThreadLimit limit(1);
    one = camera_response(camera, visibility, patches, 3);
  }
  {
    const ThreadLimit limit(2);
    two = camera_response(camera, visibility, patches, 3);
  }
  CHECK(one.R == two.R);
  CHECK(one.boundary_pixels == two.boundary_pixels);
  CHECK_THROWS_AS(camera_response(camera, visibility, patches, 0), InputError);
}
