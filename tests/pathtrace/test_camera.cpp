// Pinhole camera: geometry, orientation of the Cornell box view, ray/projection round trip, importance.
#include <catch2/catch.hpp>
#include <cmath>

#include "core/error.h"
#include "core/moments.h"
#include "core/rng.h"
#include "pathtrace/camera.h"
#include "support/stat_checks.h"

using namespace radwalk;

TEST_CASE("Cornell camera: field of view, centre ray, left/right and up/down", "[camera]") {
  const Camera c = Camera::cornell_box();
  CHECK(c.vfov * 180 / kPi == Approx(39.3077).epsilon(1e-5));
  const PinholeCamera cam(c, 256, 256);
  const Ray centre = cam.generate_ray(128, 128);
  CHECK((centre.direction - Vec3(0, 0, 1)).norm() < 1e-12);
  CHECK((centre.origin - Vec3(278, 273, -800)).norm() == 0);
  // The top edge of the film sees up at half the field of view.
  const Ray top = cam.generate_ray(128, 0);
  CHECK(std::atan2(top.direction.y(), top.direction.z()) == Approx(c.vfov / 2));
  // The red wall (x = 556) is on the left of the image, the green wall (x = 0) on the right.
  CHECK(cam.generate_ray(0, 128).direction.x() > 0);
  CHECK(cam.project(Vec3(556, 273, 559.2))->x() < 128);
  CHECK(cam.project(Vec3(0, 273, 559.2))->x() > 128);
  CHECK(cam.project(Vec3(278, 548.8, 559.2))->y() < 128);  // ceiling in the upper half
  CHECK_FALSE(cam.project(Vec3(278, 273, -900)));           // behind the camera
  CHECK_THROWS_AS(PinholeCamera(Camera{Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(0, 1, 0), 1.0}, 4, 4), InputError);
}

TEST_CASE("camera: generate_ray and project are inverse", "[camera]") {
  const Camera c{Vec3(1, 2, 3), Vec3(0.3, -0.2, 1), Vec3(0, 1, 0.1), 0.9};
  const PinholeCamera cam(c, 320, 200);
  Rng rng = stream(81, StreamDomain::test, 0);
  for (int k = 0; k < 1000; ++k) {
    const double fx = 320 * rng.uniform(), fy = 200 * rng.uniform();
    const Ray r = cam.generate_ray(fx, fy);
    const auto f = cam.project(r.origin + (1 + 10 * rng.uniform()) * r.direction);
    REQUIRE(f);
    CHECK(f->x() == Approx(fx).margin(1e-9));
    CHECK(f->y() == Approx(fy).margin(1e-9));
  }
}

TEST_CASE("camera importance integrates to 1 over each pixel's solid angle", "[camera][statistical]") {
  // H0: int_{pixel} W(w) cos(theta) dw = 1 (projected solid angle). Directions uniform in the cone around the film corner-to-corner; 3 pixels,
  // alpha = 1e-3 family-wise.
  const PinholeCamera cam(Camera{Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(0, 1, 0), 0.8}, 8, 6);
  const double z = z_critical(sidak(1e-3, 3));
  const double cos_max = std::cos(1.0);  // a cone wider than the film
  const double cone = 2 * kPi * (1 - cos_max);
  int k = 0;
  for (auto [px, py] : {std::pair{0, 0}, std::pair{3, 2}, std::pair{7, 5}}) {
    Rng rng = stream(82, StreamDomain::test, k++);
    PowerSums m;
    for (int s = 0; s < 400000; ++s) {
      const double cz = 1 - rng.uniform() * (1 - cos_max), r = std::sqrt(1 - cz * cz), phi = 2 * kPi * rng.uniform();
      const Vec3 w(r * std::cos(phi), r * std::sin(phi), cz);
      const auto f = cam.project(w);
      const bool in = f && static_cast<int>(f->x()) == px && static_cast<int>(f->y()) == py;
      m.add(in ? cam.importance(w) * cz * cone : 0.0);
    }
    radwalk::test::check_z("pixel importance", m.mean(), m.standard_error(), 1.0, z);
  }
}
