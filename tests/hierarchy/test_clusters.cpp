// Oriented clusters (hierarchy/cluster_tree.h) and the hierarchical stochastic Jacobi with clusters:
//   - push conserves power: random deposits at clusters that pass the oracle, from random shooters, pushed to the
//     members: sum_i A_i H_i equals the deposited power up to rounding (a relative 1e-12: a few hundred additions of
//     doubles), every H_i >= 0, and the members of a flat cluster all get the same irradiance;
//   - furnace with unequal faces: a closed cube whose walls are cut into faces of unequal areas (0.01 to 0.25), all
//     emitting E and reflecting rho, has B = E / (1 - rho) on every face. Each wall is one flat cluster, and with a
//     large ratio every ray is received by a cluster, which by the cosine rule gives every member the cluster's mean
//     irradiance: in the furnace that is every face's own expectation, so every face passes a t-test against
//     E / (1 - rho) (replicate standard errors, 23 degrees of freedom, family-wise alpha = 1e-3, Sidak over faces and
//     channels). A rule that shared the power equally per member (not by area) puts 25 times more irradiance on the
//     smallest face than the largest: the table rejects it (seen once by substituting that rule in cluster_push);
//   - the cluster tree: every patch in exactly one leaf cluster, members within 54.7 degrees of their group's axis,
//     parents before children.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/rng.h"
#include "core/sampling.h"
#include "hierarchy/cluster_tree.h"
#include "hierarchy/hierarchical_jacobi.h"
#include "hierarchy_test_scenes.h"
#include "patch/patch_builder.h"
#include "support/box_scenes.h"
#include "support/stat_checks.h"
#include "support/statistics.h"
#include "visibility/embree_visibility.h"

using namespace radwalk;

namespace {

// The unit cube, inward, each wall cut at the same unequal coordinates t in both directions (faces of areas from
// 0.1 x 0.1 to 0.5 x 0.5), every face reflecting rho and emitting radiance Le.
PatchSet unequal_furnace(double rho, double Le) {
  PatchBuilder b;
  const int m = b.add_material("glow", Rgb::Constant(rho), Rgb::Constant(Le));
  const double t[] = {0, 0.1, 0.35, 0.5, 1};
  struct Wall {
    Vec3 o, u, v;  // u x v = the inward normal
  };
  const Wall walls[] = {{Vec3(0, 0, 0), Vec3::UnitX(), Vec3::UnitY()}, {Vec3(0, 0, 1), Vec3::UnitY(), Vec3::UnitX()},
                        {Vec3(0, 0, 0), Vec3::UnitY(), Vec3::UnitZ()}, {Vec3(1, 0, 0), Vec3::UnitZ(), Vec3::UnitY()},
                        {Vec3(0, 0, 0), Vec3::UnitZ(), Vec3::UnitX()}, {Vec3(0, 1, 0), Vec3::UnitX(), Vec3::UnitZ()}};
  for (const Wall& w : walls)
    for (int a = 0; a < 4; ++a)
      for (int c = 0; c < 4; ++c) {
        const auto p = [&](int i, int j) { return Vec3(w.o + t[i] * w.u + t[j] * w.v); };
        b.add_quad(p(a, c), p(a + 1, c), p(a + 1, c + 1), p(a, c + 1), m);
      }
  return b.build();
}

// Patches in many orientations: the cube room's walls and tilted quads inside it.
PatchSet mixed_scene() {
  PatchBuilder b;
  const int m = b.add_material("grey", Rgb::Constant(0.5));
  test::add_box(b, Vec3(0, 0, 0), Vec3(4, 4, 4), 6, true, m);
  Rng rng = stream(3, StreamDomain::benchmark, 0);
  for (int k = 0; k < 200; ++k) {
    const Vec3 c(0.5 + 3 * rng.uniform(), 0.5 + 3 * rng.uniform(), 0.5 + 3 * rng.uniform());
    const double z = 1 - 2 * rng.uniform(), phi = 2 * kPi * rng.uniform(), sz = std::sqrt(std::max(0.0, 1 - z * z));
    const Vec3 n(sz * std::cos(phi), sz * std::sin(phi), z);
    const Frame f(n);
    const double s = 0.02 + 0.1 * rng.uniform();
    b.add_quad(c + s * (-f.t - f.b), c + s * (f.t - f.b), c + s * (f.t + f.b), c + s * (-f.t + f.b), m);
  }
  return b.build();
}

}  // namespace

TEST_CASE("cluster tree: every patch in one leaf cluster, oriented groups, parents first", "[hierarchy]") {
  const PatchSet ps = mixed_scene();
  const ClusterTree t = make_cluster_tree(ps, 4);
  REQUIRE(t.size() > 10);
  std::vector<int> count(ps.size(), 0);
  for (std::size_t c = 0; c < t.size(); ++c) {
    if (t.parent[c] >= 0) CHECK(static_cast<std::size_t>(t.parent[c]) < c);
    if (t.is_leaf(c)) {
      CHECK(t.end[c] - t.begin[c] <= 4);
      for (std::int32_t k = t.begin[c]; k < t.end[c]; ++k) ++count[static_cast<std::size_t>(t.member[static_cast<std::size_t>(k)])];
    }
    CHECK(t.cos_cone[c] <= 1 + 1e-12);
  }
  for (std::size_t i = 0; i < ps.size(); ++i) {
    CHECK(count[i] == 1);
    const std::int32_t c = t.leaf_of[i];
    REQUIRE(c >= 0);
    // Within the top cluster's group: the normal's largest component is along the same signed axis as the group's.
    std::int32_t top = c;
    while (t.parent[static_cast<std::size_t>(top)] >= 0) top = t.parent[static_cast<std::size_t>(top)];
    int k = 0;
    ps.normal[i].cwiseAbs().maxCoeff(&k);
    CHECK(ps.normal[i][k] * t.axis[static_cast<std::size_t>(top)][k] > 0);
  }
}

TEST_CASE("cluster push: the power deposited at clusters reaches their members exactly", "[hierarchy]") {
  const PatchSet ps = mixed_scene();
  const ClusterTree t = make_cluster_tree(ps, 4);
  std::vector<ClusterIrradiance> G(t.size(), ClusterIrradiance::Zero());
  Rng rng = stream(11, StreamDomain::benchmark, 1);
  Rgb deposited = Rgb::Zero();
  int taken = 0;
  for (int k = 0; k < 20000; ++k) {
    const auto c = static_cast<std::size_t>(rng.uniform_index(static_cast<std::uint32_t>(t.size())));
    const Vec3 shooter(-8 + 20 * rng.uniform(), -8 + 20 * rng.uniform(), -8 + 20 * rng.uniform());
    Vec3 w;
    if (!cluster_receives(t, c, shooter, 0.5, &w)) continue;
    const Rgb P(rng.uniform(), rng.uniform(), rng.uniform());
    cluster_deposit(t, c, P, w, G);
    deposited += P;
    ++taken;
  }
  INFO("deposits " << taken);
  REQUIRE(taken > 1000);
  const std::vector<Rgb> H = cluster_push(t, ps, G);
  Rgb received = Rgb::Zero();
  for (std::size_t i = 0; i < ps.size(); ++i) {
    CHECK((H[i] >= -1e-12 * deposited).all());
    received += ps.area[i] * H[i];
  }
  for (int ch = 0; ch < 3; ++ch) CHECK(std::abs(received[ch] - deposited[ch]) <= 1e-12 * deposited[ch]);
  // A flat cluster (one wall's faces) gives all its members the same irradiance.
  const PatchSet f = unequal_furnace(0.5, 1);
  const ClusterTree tf = make_cluster_tree(f, 8);
  std::vector<ClusterIrradiance> Gf(tf.size(), ClusterIrradiance::Zero());
  Vec3 w;
  REQUIRE(cluster_receives(tf, 0, Vec3(0.5, 0.5, 0.5), 2, &w));
  cluster_deposit(tf, 0, Rgb::Constant(1), w, Gf);
  const std::vector<Rgb> Hf = cluster_push(tf, f, Gf);
  const auto c0 = static_cast<std::size_t>(tf.member[0]);
  for (std::int32_t k = tf.begin[0]; k < tf.end[0]; ++k)
    CHECK(Hf[static_cast<std::size_t>(tf.member[static_cast<std::size_t>(k)])][0] == Approx(Hf[c0][0]).epsilon(1e-12));
  CHECK(Hf[c0][0] == Approx(1.0 / tf.area[0]).epsilon(1e-12));
}

TEST_CASE("hierarchical jacobi with clusters: furnace of unequal faces, every face unbiased", "[hierarchy]") {
  const double rho = 0.5, Le = 1 / kPi;  // E = 1, B = 2
  const PatchSet roots = unequal_furnace(rho, Le);
  const EmbreeVisibility visibility(roots);
  HierarchicalOptions o;
  o.direct_oracle = o.transport_oracle = false;  // the faces are the leaves
  o.clusters = true;
  o.cluster_ratio = 100;  // every ray taken by a cluster
  o.particles = 48000;
  o.replicates = 24;
  o.seed = 5;
  const HierarchicalResult r = solve_hierarchical(roots, visibility, o);
  INFO("clusters " << r.clusters << ", deposits at clusters " << r.cluster_deposits << " of " << r.rays << " rays");
  REQUIRE(r.clusters >= 6);
  REQUIRE(r.cluster_deposits > r.rays / 2);
  const auto L = static_cast<std::size_t>(r.B.rows());
  REQUIRE(L == roots.size());
  const double t_crit = test::t_critical(z_critical(sidak(1e-3, 3 * L)), o.replicates - 1);
  test::ZTable table("furnace faces with clusters", t_crit);
  const double B = Le * kPi / (1 - rho);
  double largest_z = 0;
  for (std::size_t k = 0; k < L; ++k)
    for (int c = 0; c < 3; ++c) {
      const auto i = static_cast<Eigen::Index>(k);
      table.add("face " + std::to_string(k) + " area " + std::to_string(roots.area[k]), r.B(i, c), r.B_se(i, c), B);
      largest_z = std::max(largest_z, std::abs(test::z_score(r.B(i, c), B, r.B_se(i, c))));
    }
  table.check();
  CHECK(largest_z <= t_crit);  // the table's verdict in one line (-s shows both numbers)
  CHECK(static_cast<double>(r.cluster_deposits) / static_cast<double>(r.rays) > 0.5);
}
