// Visibility tests: EmbreeVisibility against the double-precision BruteForceVisibility, spawn_ray (no self-hits,
// no leaks through shared edges), batches and single-precision packets equal single rays, and refusal of bad
// patch sets.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "mesh/validate.h"
#include "patch/contact_pairs.h"
#include "patch/patch_scene.h"
#include "support/box_scenes.h"
#include "visibility/brute_force_visibility.h"
#include "visibility/embree_visibility.h"
#include "visibility/ray_packet.h"
#include "visibility/ray_offset.h"

using namespace radwalk;

namespace {

// A closed cube room with mixed quads and triangles, plus a tilted quad and a triangle floating inside
// (so rays meet back faces and occluders at arbitrary angles).
PatchSet cluttered_room() {
  PatchBuilder b;
  const int m = b.add_material("white", Rgb(0.5, 0.5, 0.5));
  test::add_box(b, Vec3(0, 0, 0), Vec3(1, 1, 1), 4, true, m, true);
  b.add_quad(Vec3(0.2, 0.3, 0.3), Vec3(0.7, 0.25, 0.35), Vec3(0.75, 0.7, 0.6), Vec3(0.25, 0.75, 0.55), m);
  b.add_triangle(Vec3(0.6, 0.1, 0.8), Vec3(0.9, 0.5, 0.7), Vec3(0.5, 0.6, 0.9), m);
  return b.build();
}

Vec3 uniform_sphere(Rng& rng) {
  const double z = 1 - 2 * rng.uniform(), phi = 2 * kPi * rng.uniform();
  const double r = std::sqrt(std::max(0.0, 1 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

double distance_to_boundary(const PatchSet& ps, PatchIndex i, const Vec3& x) {
  double d = INFINITY;
  const int m = ps.corner_count(i);
  for (int k = 0; k < m; ++k) {
    const Vec3 a = ps.corner(i, k), b = ps.corner(i, (k + 1) % m);
    const double s = std::clamp((x - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    d = std::min(d, (a + s * (b - a) - x).norm());
  }
  return d;
}

// Number of rays where `a` and the reference `ref` disagree beyond float rounding: a different patch (unless the
// reference hit lies within 1e-5 of the edge of either patch, where float and double may differ), a different
// side, or |t_a - t_ref| > 1e-5 (the scene is the unit cube: float rounding is about 1e-7).
long unexplained_mismatches(const PatchSet& ps, const Visibility& a, const Visibility& ref, int rays,
                            std::uint64_t seed, long* edge_cases = nullptr) {
  Rng rng = stream(seed, StreamDomain::test, 0);
  long bad = 0, edge = 0;
  for (int k = 0; k < rays; ++k) {
    Ray ray;
    ray.origin = Vec3(rng.uniform(), rng.uniform(), rng.uniform());
    ray.direction = uniform_sphere(rng);
    const Hit h = a.intersect(ray), r = ref.intersect(ray);
    if (h.patch == r.patch && h.front == r.front && (h.missed() || std::abs(h.t - r.t) <= 1e-5)) continue;
    if (!h.missed() && !r.missed()) {
      const Vec3 x = ray.origin + r.t * ray.direction;
      if (distance_to_boundary(ps, r.patch, x) < 1e-5 || distance_to_boundary(ps, h.patch, x) < 1e-5) {
        ++edge;
        continue;
      }
    }
    if (bad < 5)
      std::printf("mismatch: ray %d: patch %d vs %d, front %d vs %d, t %.9g vs %.9g\n", k, h.patch, r.patch, h.front,
                  r.front, h.t, r.t);
    ++bad;
  }
  if (edge_cases) *edge_cases = edge;
  return bad;
}

}  // namespace

TEST_CASE("Embree agrees with brute force on random rays", "[visibility]") {
  const PatchSet ps = cluttered_room();
  const EmbreeVisibility embree(ps);
  const BruteForceVisibility brute(ps);
  long edge = 0;
  const long bad = unexplained_mismatches(ps, embree, brute, 20000, 7, &edge);
  INFO("unexplained mismatches " << bad << ", hits within 1e-5 of an edge " << edge << " of 20000 rays");
  CHECK(bad == 0);
  CHECK(edge <= 20);  // edge-near hits have probability about 1e-4 per ray here

  // The comparison rejects a wrong visibility: the same room with its tilted quad missing.
  PatchSet holed = ps;
  holed.corners[ps.size() - 2] = holed.corners[ps.size() - 1];  // quad replaced by a copy of the triangle
  const BruteForceVisibility wrong(holed);
  const long rejected = unexplained_mismatches(ps, embree, wrong, 2000, 8);
  INFO("mismatches against a room missing its tilted quad: " << rejected);
  CHECK(rejected > 50);
}

TEST_CASE("batch intersect and occluded equal single rays", "[visibility]") {
  const PatchSet ps = cluttered_room();
  const EmbreeVisibility embree(ps);
  Rng rng = stream(3, StreamDomain::test, 0);
  const std::size_t n = 1000 + 7;  // not a multiple of 16 or 256
  std::vector<Ray> rays(n);
  for (auto& r : rays) {
    r.origin = Vec3(rng.uniform(), rng.uniform(), rng.uniform());
    r.direction = uniform_sphere(rng);
    r.tmax = rng.uniform() < 0.5 ? INFINITY : 0.5 * rng.uniform();
  }
  std::vector<Hit> hits(n);
  std::unique_ptr<bool[]> occ(new bool[n]);
  embree.intersect(rays.data(), hits.data(), n);
  embree.occluded(rays.data(), occ.get(), n);
  long differ = 0, occluded_count = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const Hit h = embree.intersect(rays[k]);
    differ += h.patch != hits[k].patch || h.t != hits[k].t || h.front != hits[k].front;
    differ += embree.occluded(rays[k]) != occ[k];
    differ += occ[k] != !h.missed();  // intersect within tmax <=> occluded
    occluded_count += occ[k];
  }
  INFO("differences " << differ << ", occluded " << occluded_count << " of " << n);
  CHECK(differ == 0);
  CHECK(occluded_count > 0);
  CHECK(occluded_count < long(n));
}

TEST_CASE("a ray packet in single precision gives the hits of its rays traced one by one", "[visibility]") {
  // Packets of every size 1..16 (the lanes past the count hold rays that must be ignored): Embree's packet
  // path and the interface's default (BruteForceVisibility) both equal their single-ray intersect of
  // packet.ray(k).
  const PatchSet ps = cluttered_room();
  const EmbreeVisibility embree(ps);
  const BruteForceVisibility brute(ps);
  Rng rng = stream(4, StreamDomain::test, 0);
  long differ = 0, hits = 0;
  auto same = [](const Hit& a, const Hit& b) {
    return a.patch == b.patch && a.t == b.t && a.front == b.front;
  };
  for (std::size_t count = 1; count <= kPacketSize; ++count)
    for (int trial = 0; trial < 20; ++trial) {
      RayPacket packet;
      for (std::size_t k = 0; k < kPacketSize; ++k) {
        Ray r;
        r.origin = Vec3(rng.uniform(), rng.uniform(), rng.uniform());
        r.direction = uniform_sphere(rng);
        r.tmax = rng.uniform() < 0.5 ? INFINITY : 0.5 * rng.uniform();
        packet.set(k, r);
      }
      packet.count = count;
      Hit from_embree[kPacketSize], from_brute[kPacketSize];
      embree.intersect(packet, from_embree);
      brute.intersect(packet, from_brute);
      for (std::size_t k = 0; k < count; ++k) {
        differ += !same(from_embree[k], embree.intersect(packet.ray(k)));
        differ += !same(from_brute[k], brute.intersect(packet.ray(k)));
        hits += !from_embree[k].missed();
      }
    }
  INFO("differences " << differ << ", hits " << hits);
  CHECK(differ == 0);
  CHECK(hits > 0);
}

TEST_CASE("spawned rays never hit their own patch and never leak from a closed room", "[visibility]") {
  // Origins on edges and corners (u at 0 or just below 1) as well as inside the patches.
  const PatchSet ps = test::unit_cube_room(4, true);
  const EmbreeVisibility embree(ps);
  const double eps = ray_epsilon(ps);
  long self = 0, escaped = 0, back = 0, rays = 0;
  const double corner_u[] = {0.0, 0x1.fffffffffffffp-1, 0.5};
  for (std::size_t i = 0; i < ps.size(); ++i) {
    Rng rng = stream(11, StreamDomain::test, i);
    const Frame frame(ps.normal[i]);
    for (int k = 0; k < 2000; ++k, ++rays) {
      const double u1 = k < 9 ? corner_u[k % 3] : rng.uniform();
      const double u2 = k < 9 ? corner_u[k / 3] : rng.uniform();
      const Vec3 p = sample_patch_point(ps, i, u1, u2);
      const Vec3 w = frame.to_world(sample_cosine_hemisphere(rng.uniform(), rng.uniform()));
      const Hit h = embree.intersect(spawn_ray(ps, i, p, w, eps));
      self += h.patch == PatchIndex(i);
      escaped += h.missed();
      back += !h.missed() && !h.front;
    }
  }
  INFO("rays " << rays << ": self hits " << self << ", escaped " << escaped << ", back hits " << back
               << ", eps " << eps);
  CHECK(self == 0);
  CHECK(escaped == 0);
  CHECK(back == 0);
}

TEST_CASE("spawn_ray offsets: eps off the plane, at least eps inside every edge", "[visibility]") {
  PatchBuilder b;
  const int m = b.add_material("white", Rgb(0.5, 0.5, 0.5));
  b.add_quad(Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(4, 1, 0), Vec3(0, 1, 0), m);  // thin quad, normal +z
  b.add_triangle(Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 3, 1), m);
  const PatchSet ps = b.build();
  const double eps = ray_epsilon(ps);
  CHECK(eps == Approx(std::max(1e-6 * 4, 8 * 1.1920929e-7 * 4)));
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const int n = ps.corner_count(i);
    double radius = 0, d = INFINITY;  // largest centroid-corner distance, smallest centroid-edge-line distance
    for (int k = 0; k < n; ++k) {
      const Vec3 a = ps.corner(i, k), e = ps.corner(i, (k + 1) % n) - a;
      radius = std::max(radius, (ps.centroid[i] - a).norm());
      d = std::min(d, e.cross(ps.centroid[i] - a).norm() / e.norm());
    }
    for (int k = 0; k < n; ++k) {
      const Vec3 a = ps.corner(i, k), e = ps.corner(i, (k + 1) % n) - a;
      for (const double s : {0.0, 0.3, 1.0}) {
        const Vec3 p = a + s * e;
        for (const double side : {1.0, -1.0}) {
          const Ray r = spawn_ray(ps, i, p, side * ps.normal[i], eps);
          const double height = (r.origin - p).dot(ps.normal[i]);
          const Vec3 in_plane = r.origin - height * ps.normal[i];
          const double edge_distance = e.cross(in_plane - a).norm() / e.norm();
          INFO("patch " << i << " edge " << k << " s " << s << ": height " << height << ", distance to edge line "
                        << edge_distance << ", eps " << eps);
          CHECK(height == Approx(side * eps).epsilon(1e-9));
          CHECK(edge_distance >= eps * (1 - 1e-9));
          CHECK((in_plane - p).norm() <= eps * radius / d * (1 + 1e-9));  // bounded bias: eps * r_i / d_i
        }
      }
    }
  }
}

TEST_CASE("front and back faces and tmax", "[visibility]") {
  PatchBuilder b;
  const int m = b.add_material("white", Rgb(0.5, 0.5, 0.5));
  b.add_quad(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), m);  // normal +z
  const PatchSet ps = b.build();
  const EmbreeVisibility embree(ps);
  const BruteForceVisibility brute(ps);
  for (const Visibility* v : {static_cast<const Visibility*>(&embree), static_cast<const Visibility*>(&brute)}) {
    Ray down{Vec3(0.3, 0.6, 2), Vec3(0, 0, -1)};
    Hit h = v->intersect(down);
    CHECK(h.patch == 0);
    CHECK(h.front);
    CHECK(h.t == Approx(2.0).epsilon(1e-6));
    Ray up{Vec3(0.3, 0.6, -1), Vec3(0, 0, 1)};
    h = v->intersect(up);
    CHECK(h.patch == 0);
    CHECK_FALSE(h.front);
    up.tmax = 0.5;
    CHECK(v->intersect(up).missed());
    CHECK_FALSE(v->occluded(up));
    Ray away{Vec3(1.5, 0.5, 1), Vec3(0, 0, -1)};
    CHECK(v->intersect(away).missed());
  }
}

TEST_CASE("bad patch sets are refused", "[visibility]") {
  PatchSet ps = test::unit_cube_room(1);
  PatchSet bad_index = ps;
  bad_index.corners[2][1] = std::int32_t(ps.points.size());
  CHECK_THROWS_AS(EmbreeVisibility(bad_index), InputError);
  PatchSet bad_point = ps;
  bad_point.points[0].x() = NAN;
  CHECK_THROWS_AS(EmbreeVisibility(bad_point), InputError);
  EmbreeOptions bad_device;
  bad_device.device_config = "isa=no_such_isa";
  // Embree ignores or refuses unknown settings; either way no crash, and a refusal is an exception.
  try {
    const EmbreeVisibility v(ps, bad_device);
    CHECK(v.patch_count() == 6);
  } catch (const std::runtime_error& e) {
    INFO(e.what());
    CHECK(std::string(e.what()).find("embree") != std::string::npos);
  }
}

namespace {

// A 4 x 4 floor (normal +y) with a unit box standing on [1, 2] x [1, 2] (sides and top facing out, a bottom facing
// down onto the floor), patched as the CLI does with --max-edge 4: the floor is cut along the box's footprint, so
// that its piece under the box and the box's bottom are a contact pair (patch/contact_pairs.h).
PatchSet box_on_cut_floor(bool two_sided_floor) {
  Mesh m;
  m.path = "generated";
  auto v = [&](double x, double y, double z) {
    m.vertices.push_back({x, y, z});
    return static_cast<std::int32_t>(m.vertices.size() - 1);
  };
  auto quad = [&](std::int32_t a, std::int32_t b, std::int32_t c, std::int32_t d, std::int32_t material) {
    m.faces.push_back({a, b, c, d});
    m.face_material.push_back(material);
  };
  quad(v(0, 0, 0), v(0, 0, 4), v(4, 0, 4), v(4, 0, 0), 0);
  const auto b0 = v(1, 0, 1), b1 = v(2, 0, 1), b2 = v(2, 0, 2), b3 = v(1, 0, 2);
  const auto t0 = v(1, 1, 1), t1 = v(2, 1, 1), t2 = v(2, 1, 2), t3 = v(1, 1, 2);
  quad(b1, b0, t0, t1, 1);  // z = 1, normal -z
  quad(b2, b1, t1, t2, 1);  // x = 2, normal +x
  quad(b3, b2, t2, t3, 1);  // z = 2, normal +z
  quad(b0, b3, t3, t0, 1);  // x = 1, normal -x
  quad(t0, t3, t2, t1, 1);  // top, normal +y
  quad(b0, b1, b2, b3, 1);  // bottom, normal -y: onto the floor
  Material floor, box;
  floor.name = "floor";
  floor.Kd = Rgb(0.5, 0.5, 0.5);
  floor.two_sided = two_sided_floor;
  box.name = "box";
  box.Kd = Rgb(0.4, 0.4, 0.4);
  m.materials = {floor, box};
  validate_mesh(m);
  ScenePatchingOptions o;
  o.split.max_edge = 4;
  return patch_scene(std::move(m), o).patches;
}

}  // namespace

TEST_CASE("a ray from inside a box standing on a cut floor hits the box's bottom, never the floor piece under it",
          "[visibility][contact]") {
  for (const bool two_sided_floor : {false, true}) {
    INFO("two-sided floor " << two_sided_floor);
    const PatchSet ps = box_on_cut_floor(two_sided_floor);
    const std::vector<std::int32_t> pair = contact_pair_ids(ps);
    // The pair: the floor piece under the box (normal +y) and the bottom (normal -y).
    PatchIndex piece = -1, bottom = -1;
    for (std::size_t i = 0; i < ps.size(); ++i)
      if (pair[i] == 0) (ps.normal[i].y() > 0 ? piece : bottom) = PatchIndex(i);
    REQUIRE(piece >= 0);
    REQUIRE(bottom >= 0);
    const EmbreeVisibility embree(ps);
    const BruteForceVisibility brute(ps);
    // Rays from points inside the box, down through its bottom, and from points below the floor, up through the
    // floor piece: single rays and packets, the first always reaching the bottom's back, the second the piece's.
    Rng rng = stream(7, StreamDomain::test, 0);
    std::vector<Ray> down, up;
    for (int k = 0; k < 4096; ++k) {
      const double x = 1 + 0.9 * rng.uniform() + 0.05, z = 1 + 0.9 * rng.uniform() + 0.05;
      // Directions steep enough to reach the plane y = 0 inside the footprint from the height chosen.
      const double h = 0.05 + 0.9 * rng.uniform();
      const double dx = (1 + 0.05 - x + 0.9 * rng.uniform()), dz = (1 + 0.05 - z + 0.9 * rng.uniform());
      const Vec3 d = Vec3(dx, -h, dz).normalized();
      down.push_back(Ray{Vec3(x, h, z), d});
      up.push_back(Ray{Vec3(x + dx, -h, z + dz), Vec3(-d.x(), -d.y(), -d.z())});
    }
    std::vector<Hit> down_hits(down.size()), up_hits(up.size());
    embree.intersect(down.data(), down_hits.data(), down.size());
    embree.intersect(up.data(), up_hits.data(), up.size());
    // Hits that are not the expected one, of Embree (single rays and packets) and of the brute-force reference.
    std::size_t embree_wrong = 0, brute_wrong = 0;
    const auto down_ok = [&](const Hit& h, const Ray& r) {
      return h.patch == bottom && !h.front && std::abs(h.t - r.origin.y() / -r.direction.y()) < 1e-5;
    };
    // A two-sided floor: the piece's own back patch (facing down, seen from its front); else the piece's back.
    const auto up_ok = [&](const Hit& h) {
      return two_sided_floor ? h.patch >= 0 && ps.side[std::size_t(h.patch)] == Side::back &&
                                   ps.face[std::size_t(h.patch)] == ps.face[std::size_t(piece)] && h.front
                             : h.patch == piece && !h.front;
    };
    for (std::size_t k = 0; k < down.size(); ++k) {
      embree_wrong += !down_ok(embree.intersect(down[k]), down[k]) + !down_ok(down_hits[k], down[k]);
      brute_wrong += !down_ok(brute.intersect(down[k]), down[k]);
      embree_wrong += !up_ok(embree.intersect(up[k])) + !up_ok(up_hits[k]);
      brute_wrong += !up_ok(brute.intersect(up[k]));
    }
    CHECK(embree_wrong == 0);
    CHECK(brute_wrong == 0);
  }
}
