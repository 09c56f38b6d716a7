// Adaptive patching in the patch layer: split_patches tiles its parents exactly, edge_neighbours finds coplanar
// patches sharing (part of) an edge, and the refinement criterion marks exactly the patches it should.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "mesh/read_scene.h"
#include "mesh/validate.h"
#include "patch/patch_builder.h"
#include "patch/patch_neighbours.h"
#include "patch/patching.h"
#include "patch/refine.h"
#include "patch/refine_criterion.h"

using namespace radwalk;

namespace {

std::string bundled(const std::string& name) { return std::string(RADWALK_SOURCE_DIR) + "/meshes/" + name; }

PatchSet cornell(double max_edge) {
  Mesh mesh = read_scene(bundled("cornell_box.obj"));
  validate_mesh(mesh);
  return make_patches(mesh, max_edge);
}

std::map<int, double> area_per_face(const PatchSet& p) {
  std::map<int, double> a;
  for (std::size_t i = 0; i < p.size(); ++i) a[p.face[i]] += p.area[i];
  return a;
}

// Children's areas add up to the parent's and their normals are the parent's, to `eps` (rounding for flat
// patches; the Cornell box's measured quads are slightly non-planar, which costs O(twist^2), about 1e-8).
void check_tiling(const PatchSet& before, const std::vector<bool>& split, double eps = 1e-12) {
  std::vector<std::int32_t> parent;
  const PatchSet after = split_patches(before, split, &parent);
  std::size_t splits = 0;
  for (bool s : split) splits += s;
  REQUIRE(after.size() == before.size() + 3 * splits);
  REQUIRE(parent.size() == after.size());
  std::vector<double> child_area(before.size(), 0.0);
  std::vector<int> children(before.size(), 0);
  for (std::size_t k = 0; k < after.size(); ++k) {
    const auto i = std::size_t(parent[k]);
    child_area[i] += after.area[k];
    ++children[i];
    INFO("patch " << k << " from " << i);
    CHECK(after.face[k] == before.face[i]);
    CHECK(after.material[k] == before.material[i]);
    CHECK((after.rho[k] == before.rho[i]).all());
    CHECK((after.E[k] == before.E[i]).all());
    CHECK(after.is_quad(k) == before.is_quad(i));
    CHECK(after.normal[k].dot(before.normal[i]) > 1 - eps);
    CHECK(after.area[k] > 0);
    if (split[i]) CHECK(after.area[k] < before.area[i]);
  }
  for (std::size_t i = 0; i < before.size(); ++i) {
    INFO("parent " << i);
    CHECK(children[i] == (split[i] ? 4 : 1));
    CHECK(child_area[i] == Approx(before.area[i]).epsilon(eps));
  }
  CHECK(after.total_area() == Approx(before.total_area()).epsilon(eps));
  const auto a = area_per_face(before), b = area_per_face(after);
  for (const auto& [face, area] : a) CHECK(b.at(face) == Approx(area).epsilon(eps));
}

}  // namespace

TEST_CASE("split_patches: children tile their parent (area, face, rho, E, orientation)", "[patch][refine]") {
  SECTION("Cornell box quads, every other patch split, then twice more") {
    PatchSet p = cornell(200);
    std::vector<bool> split(p.size());
    for (std::size_t i = 0; i < p.size(); i += 2) split[i] = true;
    check_tiling(p, split, 1e-6);
    for (int round = 0; round < 2; ++round) {
      p = split_patches(p, split);
      split.assign(p.size(), false);
      for (std::size_t i = 0; i < p.size(); i += 3) split[i] = true;
      check_tiling(p, split, 1e-6);
    }
  }
  SECTION("triangles and quads of a PatchBuilder set") {
    PatchBuilder b;
    const int m = b.add_material("grey", Rgb(0.5, 0.4, 0.3), Rgb(1, 2, 3));
    b.add_triangle(Vec3(0, 0, 0), Vec3(3, 0, 0), Vec3(1, 2, 0.5), m);
    b.add_quad(Vec3(0, 0, 1), Vec3(2, 0, 1), Vec3(2.5, 1, 1), Vec3(-0.5, 1.5, 1), m);
    const PatchSet p = b.build();
    check_tiling(p, {true, true});
    check_tiling(p, {true, false});
  }
  SECTION("bad input") {
    const PatchSet p = cornell(0);
    CHECK_THROWS_AS(split_patches(p, std::vector<bool>(p.size() + 1)), InternalError);
  }
}

TEST_CASE("split_patches: two split neighbours share their edge midpoint (no crack)", "[patch][refine]") {
  const PatchSet p = cornell(0);
  const PatchSet q = split_patches(p, std::vector<bool>(p.size(), true));
  // Conforming input fully split stays conforming: every point is distinct.
  std::map<std::array<double, 3>, int> seen;
  for (const Vec3& x : q.points) ++seen[{x.x(), x.y(), x.z()}];
  for (const auto& [x, count] : seen) CHECK(count == 1);
}

TEST_CASE("edge_neighbours: coplanar patches sharing all or part of an edge", "[patch][refine]") {
  // Three unit squares in a row on z = 0 (0 | 1 | 2), a wall standing on the far edge of 2 (3, a crease), a square
  // touching 0 only at a corner (4), and a square on z = 0 facing down next to 0 (5: opposite normal).
  PatchBuilder b;
  const int m = b.add_material("white", Rgb(0.5, 0.5, 0.5));
  b.add_quad(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), m);
  b.add_quad(Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(2, 1, 0), Vec3(1, 1, 0), m);
  b.add_quad(Vec3(2, 0, 0), Vec3(3, 0, 0), Vec3(3, 1, 0), Vec3(2, 1, 0), m);
  b.add_quad(Vec3(3, 0, 0), Vec3(3, 0, 1), Vec3(3, 1, 1), Vec3(3, 1, 0), m);
  b.add_quad(Vec3(-1, -1, 0), Vec3(0, -1, 0), Vec3(0, 0, 0), Vec3(-1, 0, 0), m);
  b.add_quad(Vec3(0, 1, 0), Vec3(0, 2, 0), Vec3(1, 2, 0), Vec3(1, 1, 0), m);
  const PatchSet p = b.build();
  using Pairs = std::vector<std::pair<PatchIndex, PatchIndex>>;
  CHECK(edge_neighbours(p) == Pairs{{0, 1}, {1, 2}});

  // Split 1: its children meet 0 and 2 along half edges (T-junctions) and each other along whole edges.
  std::vector<std::int32_t> parent;
  const PatchSet q = split_patches(p, {false, true, false, false, false, false}, &parent);
  // Children 1..4: (1,0)-(1.5,0)-(1.5,.5)-(1,.5) [1], (1.5,0)-(2,0)-.. [2], centre-(2,1) [3], (1,.5)-(1.5,1) [4].
  CHECK(edge_neighbours(q) == Pairs{{0, 1}, {0, 4}, {1, 2}, {1, 4}, {2, 3}, {2, 5}, {3, 4}, {3, 5}});
}

TEST_CASE("radiosity_jumps: marks exactly the patches that differ from a neighbour by more than tol",
          "[patch][refine]") {
  // A strip of four squares on z = 0 with rho 0.5, a light (rho 0.8, E = 10) set into the strip's end, and a wall
  // on the far edge of the strip (a crease: not a neighbour).
  PatchBuilder b;
  const int white = b.add_material("white", Rgb(0.5, 0.5, 0.5));
  const int light = b.add_material("light", Rgb(0.8, 0.8, 0.8), Rgb::Constant(10 / kPi));
  const int red = b.add_material("red", Rgb(0.5, 0.0, 0.0));
  for (int k = 0; k < 4; ++k)
    b.add_quad(Vec3(k, 0, 0), Vec3(k + 1, 0, 0), Vec3(k + 1, 1, 0), Vec3(k, 1, 0), white);
  b.add_quad(Vec3(4, 0, 0), Vec3(5, 0, 0), Vec3(5, 1, 0), Vec3(4, 1, 0), light);       // 4
  b.add_quad(Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(0, 1, 1), Vec3(0, 0, 1), red);         // 5, wall at x = 0
  const PatchSet p = b.build();
  const auto neighbours = edge_neighbours(p);
  using Pairs = std::vector<std::pair<PatchIndex, PatchIndex>>;
  REQUIRE(neighbours == Pairs{{0, 1}, {1, 2}, {2, 3}, {3, 4}});

  // H = (B - E) / rho: 2, 2, 2.2, 4 on the strip, 4 under the light (B = 10 + 0.8 x 4 = 13.2: same irradiance as
  // patch 3, so no jump there although B differs a lot), 1000 on the wall (not compared across the crease; with no
  // coplanar neighbour it gets jump 1).
  PatchRgb B(6, 3);
  B.row(0) = Rgb::Constant(1.0).transpose();
  B.row(1) = Rgb::Constant(1.0).transpose();
  B.row(2) = Rgb::Constant(1.1).transpose();
  B.row(3) = Rgb::Constant(2.0).transpose();
  B.row(4) = Rgb::Constant(13.2).transpose();
  B.row(5) = Rgb(500, 0, 0).transpose();
  JumpOptions no_floor;
  no_floor.floor_fraction = 0;
  const std::vector<double> jump = radiosity_jumps(p, B, neighbours, no_floor);
  CHECK(jump[0] == Approx(0.0).margin(1e-12));
  CHECK(jump[1] == Approx(0.2 / 2.2));
  CHECK(jump[2] == Approx(1.8 / 4));
  CHECK(jump[3] == Approx(1.8 / 4));
  CHECK(jump[4] == Approx(0.0).margin(1e-9));
  CHECK(jump[5] == 1.0);  // no coplanar neighbour: cannot be judged, so always split
  CHECK(mark_jumps(jump, 0.3) == std::vector<bool>{false, false, true, true, false, true});
  CHECK(mark_jumps(jump, 0.05) == std::vector<bool>{false, true, true, true, false, true});

  // The floor: with every value below it, differences are measured against the floor, not each other.
  PatchRgb dark = B;
  dark.row(0) = Rgb::Constant(1e-4).transpose();
  dark.row(1) = Rgb::Constant(2e-4).transpose();  // H: 2e-4 vs 4e-4, relative 0.5, absolute tiny
  const std::vector<double> floored = radiosity_jumps(p, dark, neighbours);  // floor 1 % of the mean H
  CHECK(radiosity_jumps(p, dark, neighbours, no_floor)[0] == Approx(0.5));
  CHECK(floored[0] < 0.01);

  // Noise: with standard errors 0.1 on H, the 0.2 difference between 1 and 2 is within 3 sigma (3 x 0.141),
  // the 1.8 difference between 2 and 3 is not.
  JumpOptions noisy = no_floor;
  noisy.H_se = PatchRgb::Constant(6, 3, 0.1);
  noisy.noise_z = 3;
  CHECK(mark_jumps(radiosity_jumps(p, B, neighbours, noisy), 0.05) ==
        std::vector<bool>{false, false, true, true, false, true});

  // Invisible patches (visible fraction 0) compare with nobody: ignoring 3 leaves 2 judged against 1 only, and 4 (whose only neighbour
  // is 3) at 0.
  JumpOptions ignoring = no_floor;
  ignoring.visible = {1, 1, 1, 0, 1, 1};
  const std::vector<double> j3 = radiosity_jumps(p, B, neighbours, ignoring);
  CHECK(j3[2] == Approx(0.2 / 2.2));
  CHECK(j3[3] == 0.0);
  CHECK(j3[4] == 0.0);

  CHECK_THROWS_AS(radiosity_jumps(p, PatchRgb(3, 3), neighbours), InternalError);
  JumpOptions bad;
  bad.floor_fraction = -1;
  CHECK_THROWS_AS(radiosity_jumps(p, B, neighbours, bad), InputError);
  bad = JumpOptions{};
  bad.visible = {1};
  CHECK_THROWS_AS(radiosity_jumps(p, B, neighbours, bad), InternalError);
  bad.visible = {1, 1, 1, 1.5, 1, 1};
  CHECK_THROWS_AS(radiosity_jumps(p, B, neighbours, bad), InputError);

  // Half of patch 1 hidden (under a block): its visible half has H = 2 / 0.5 = 4, like patch 3, and differs from
  // patch 0 (H = 2) by 0.5 and from patch 2 (H = 2.2) by 1.8 / 4.
  JumpOptions half = no_floor;
  half.visible = {1, 0.5, 1, 1, 1, 1};
  const std::vector<double> jh = radiosity_jumps(p, B, neighbours, half);
  CHECK(jh[0] == Approx(0.5));
  CHECK(jh[1] == Approx(0.5));
  CHECK(jh[2] == Approx(1.8 / 4));
}
