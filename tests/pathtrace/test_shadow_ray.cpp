// SurfaceGeometry::spawn_shadow_ray on facets (FacetGeometry): the segment from a vertex to a light point stops
// short of the light's plane, so an occlusion query answers "is anything between x and y", on Embree and on the
// double-precision brute force alike.
#include <catch2/catch.hpp>

#include <utility>

#include "core/rng.h"
#include "pathtrace/facet_geometry.h"
#include "scenes.h"
#include "visibility/brute_force_visibility.h"
#include "visibility/embree_visibility.h"

namespace radwalk {
namespace {

// Every (receiver point, lamp point) pair of `p` from a fixed stream, as (receiver patch, x, y) to `check`.
template <class Check>
void for_light_pairs(const PatchSet& p, const FacetGeometry& geometry, PatchIndex lamp, Check&& check) {
  Rng rng = Rng::from_family(stream_family(17, StreamDomain::test, 0), 0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (static_cast<PatchIndex>(i) == lamp) continue;
    for (int s = 0; s < 16; ++s) {
      const Vec3 x = geometry.sample_point(static_cast<PatchIndex>(i), rng.uniform(), rng.uniform());
      const Vec3 y = geometry.sample_point(lamp, rng.uniform(), rng.uniform());
      check(static_cast<PatchIndex>(i), x, y);
    }
  }
}

PatchIndex lamp_of(const PatchSet& p) {
  for (std::size_t i = 0; i < p.size(); ++i)
    if ((p.E[i] > 0).any()) return static_cast<PatchIndex>(i);
  return -1;
}

// A scene with one emitting patch, its facets, both visibilities, the lamp and its normal.
struct LampScene {
  explicit LampScene(PatchSet patches)
      : p(std::move(patches)), geometry(p), embree(p), brute(p), lamp(lamp_of(p)),
        n_y(lamp >= 0 ? p.normal[static_cast<std::size_t>(lamp)] : Vec3::Zero()) {}
  PatchSet p;
  FacetGeometry geometry;
  EmbreeVisibility embree;
  BruteForceVisibility brute;
  PatchIndex lamp;
  Vec3 n_y;
};

}  // namespace

TEST_CASE("shadow segments in an empty box reach the light unoccluded and stop before its plane", "[pathtrace]") {
  const LampScene scene(test::lit_box(Rgb::Constant(0.5), Rgb::Constant(3.0)));
  const auto& [p, geometry, embree, brute, lamp, n_y] = scene;
  REQUIRE(lamp >= 0);
  long tested = 0;
  for_light_pairs(p, geometry, lamp, [&](PatchIndex i, const Vec3& x, const Vec3& y) {
    const Vec3 w = (y - x).normalized();
    if (!(-w.dot(n_y) > 0) || !(p.normal[static_cast<std::size_t>(i)].dot(w) > 0)) return;  // back-facing pair
    const Ray ray = geometry.spawn_shadow_ray(i, x, w, (y - x).norm(), y, n_y);
    if (!(ray.tmax > 0)) return;  // grazing pair: no segment
    ++tested;
    const Vec3 end = ray.origin + ray.tmax * ray.direction;
    CHECK(n_y.dot(end - y) > 0);  // the segment's end is in front of the light's plane
    CHECK(ray.tmax < (y - x).norm());
    CHECK_FALSE(brute.occluded(ray));
    CHECK_FALSE(embree.occluded(ray));
  });
  // The ceiling's other cells are coplanar with the lamp (cos = 0): most pairs are from the walls and the floor.
  CHECK(tested > static_cast<long>(p.size()) * 16 / 2);
}

TEST_CASE("shadow segments through an obstacle are occluded", "[pathtrace]") {
  // A cube hangs under the lamp (centre of the ceiling y = 0.8): every segment from the floor's middle cell
  // straight up to the lamp passes through it.
  PatchBuilder b;
  const int wall = b.add_material("wall", Rgb::Constant(0.5));
  const int lamp_material = b.add_material("lamp", Rgb::Constant(0.5), Rgb::Constant(3.0));
  test::add_cube_outward(b, Vec3(0.3, 0.3, 0.5), 0.4, wall);
  const LampScene scene(test::closed_box(Vec3(1, 0.8, 1.3), 3, b, [&](int f, int a, int c) {
    return (f == 3 && a == 1 && c == 1) ? lamp_material : wall;
  }));
  const auto& [p, geometry, embree, brute, lamp, n_y] = scene;
  REQUIRE(lamp >= 0);
  long tested = 0;
  for_light_pairs(p, geometry, lamp, [&](PatchIndex i, const Vec3& x, const Vec3& y) {
    // Receivers on the floor (y = 0) with x in (0.34, 0.66) and z in (0.6, 0.86), below the cube (x in
    // (0.3, 0.7), z in (0.5, 0.9), y in (0.3, 0.7)); the lamp spans x, z in (1/3, 2/3) x (1.3/3, 2.6/3), so every
    // segment from there to it enters the cube's bottom face (at y = 0.3 its z is still above 0.53).
    if (std::abs(x.y()) > 1e-12 || x.x() < 0.34 || x.x() > 0.66 || x.z() < 0.6 || x.z() > 0.86) return;
    const Vec3 w = (y - x).normalized();
    const Ray ray = geometry.spawn_shadow_ray(i, x, w, (y - x).norm(), y, n_y);
    REQUIRE(ray.tmax > 0);
    ++tested;
    CHECK(brute.occluded(ray));
    CHECK(embree.occluded(ray));
  });
  CHECK(tested > 0);
}

}  // namespace radwalk
