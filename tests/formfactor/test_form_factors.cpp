// Form factors by ray shooting against closed-form and exact polygon view factors.
//
// Every Monte Carlo check is a two-sided z-test of an estimate against its exact value with the estimated
// binomial standard error sqrt(p (1 - p) / n) (conservative for the stratified estimator, see form_factors.h).
// Each TEST_CASE is one family at level alpha = 1e-3, Sidak-corrected over its m checks (Sidak's inequality holds
// for two-sided tests of jointly normal estimates with any correlation, so also for multinomial rows).
#include <catch2/catch.hpp>

#include <cstdio>
#include <map>
#include <numeric>

#include "core/error.h"
#include "core/morton.h"
#include "core/parallel.h"
#include "formfactor/form_factors.h"
#include "support/box_scenes.h"
#include "support/reference_problems.h"
#include "support/stat_checks.h"
#include "support/view_factors.h"
#include "visibility/embree_visibility.h"

using namespace radwalk;

namespace {

constexpr double kAlpha = 1e-3;

double entry(const SparseF& F, int i, int j) { return F.coeff(i, j); }

// z-score of an estimated fraction p_hat from n rays against the exact p (binomial se from p_hat).
double z_score(double p_hat, double p, double n) { return test::z_score(p_hat, p, test::binomial_se(p_hat, n)); }

// Two squares facing each other: patch 0 at z = 0 (normal +z), patch 1 at z = 1 (normal -z, or +z when
// `second_faces_away`).
PatchSet parallel_squares(bool second_faces_away = false) {
  PatchBuilder b;
  const int m = b.add_material("white", Rgb(0.5, 0.5, 0.5));
  b.add_quad(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), m);
  if (second_faces_away)
    b.add_quad(Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1), m);
  else
    b.add_quad(Vec3(0, 0, 1), Vec3(0, 1, 1), Vec3(1, 1, 1), Vec3(1, 0, 1), m);
  return b.build();
}

std::vector<Vec3> regular_polygon(double r, int sides, double z, bool facing_up) {
  std::vector<Vec3> p;
  for (int k = 0; k < sides; ++k) {
    const double phi = 2 * kPi * (facing_up ? k : -k) / sides;
    p.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
  }
  return p;
}

}  // namespace

TEST_CASE("reference view factors: closed forms and the polygon contour integral agree", "[formfactor]") {
  CHECK(test::parallel_rectangles(1, 1, 1) == Approx(test::kOpposite).epsilon(1e-8));
  CHECK(test::perpendicular_rectangles(1, 1, 1) == Approx(test::kAdjacent).epsilon(1e-8));
  CHECK(test::coaxial_disks(1, 1, 1) == Approx(0.381966).epsilon(1e-5));
  // Unit cube closure: opposite + 4 adjacent = 1.
  CHECK(test::parallel_rectangles(1, 1, 1) + 4 * test::perpendicular_rectangles(1, 1, 1) == Approx(1).epsilon(1e-8));
  const PatchSet ps = parallel_squares();
  std::vector<Vec3> a, b;
  for (int k = 0; k < 4; ++k) {
    a.push_back(ps.corner(0, k));
    b.push_back(ps.corner(1, k));
  }
  const double contour = test::polygon_exchange_area(a, b);
  INFO("contour integral " << contour << " vs closed form " << test::parallel_rectangles(1, 1, 1));
  CHECK(contour == Approx(test::parallel_rectangles(1, 1, 1)).epsilon(1e-9));
  // A 2 x 0.5 rectangle pair at distance 0.7 (non-square, other scale).
  const std::vector<Vec3> r1 = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 0.5, 0), Vec3(0, 0.5, 0)};
  const std::vector<Vec3> r2 = {Vec3(0, 0, 0.7), Vec3(0, 0.5, 0.7), Vec3(2, 0.5, 0.7), Vec3(2, 0, 0.7)};
  CHECK(test::polygon_exchange_area(r1, r2, 4, 16) / 1.0 == Approx(test::parallel_rectangles(2, 0.5, 0.7)).epsilon(1e-8));
}

TEST_CASE("parallel squares: F12 and the escape fraction in an open scene", "[formfactor]") {
  const PatchSet ps = parallel_squares();
  const EmbreeVisibility vis(ps);
  FormFactorOptions opt;
  opt.rays_per_patch = 200000;
  const FormFactors ff = estimate_form_factors(ps, vis, opt);
  const double exact = test::parallel_rectangles(1, 1, 1), n = opt.rays_per_patch;
  const double zc = z_critical(sidak(kAlpha, 4));
  test::ZTable table("F12 and escapes", zc);
  for (int i = 0; i < 2; ++i) {
    const double f = entry(ff.F, i, 1 - i), escape = ff.escaped[i] / n;
    table.add("row " + std::to_string(i) + " F", f, test::binomial_se(f, n), exact);
    table.add("row " + std::to_string(i) + " escaped", escape, test::binomial_se(escape, n), 1 - exact);
    CHECK(ff.back_hits[i] == 0);
    CHECK(entry(ff.F, i, i) == 0);
    CHECK(ff.rays[i] == opt.rays_per_patch);
    // Every ray is accounted for: front hits + escapes = rays.
    CHECK(std::lround(f * n) + ff.escaped[i] == ff.rays[i]);
  }
  table.check();
}

TEST_CASE("perpendicular squares sharing an edge", "[formfactor]") {
  PatchBuilder b;
  const int m = b.add_material("white", Rgb(0.5, 0.5, 0.5));
  b.add_quad(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), m);  // floor, normal +z
  b.add_quad(Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 0, 0), m);  // wall y = 0, normal +y
  const PatchSet ps = b.build();
  REQUIRE(ps.normal[1].y() == Approx(1));
  const EmbreeVisibility vis(ps);
  FormFactorOptions opt;
  opt.rays_per_patch = 200000;
  const FormFactors ff = estimate_form_factors(ps, vis, opt);
  const double exact = test::perpendicular_rectangles(1, 1, 1), n = opt.rays_per_patch;
  const double zc = z_critical(sidak(kAlpha, 2));
  test::ZTable table("perpendicular F", zc);
  for (int i = 0; i < 2; ++i) {
    const double f = entry(ff.F, i, 1 - i);
    table.add("row " + std::to_string(i), f, test::binomial_se(f, n), exact);
    CHECK(ff.back_hits[i] == 0);
  }
  table.check();
}

TEST_CASE("unit cube: closure, closed forms, reciprocity, and the test rejects a wrong value", "[formfactor]") {
  const PatchSet ps = test::unit_cube_room(1);  // patches x=0, x=1, y=0, y=1, z=0, z=1
  const EmbreeVisibility vis(ps);
  for (const bool stratified : {true, false}) {
    FormFactorOptions opt;
    opt.rays_per_patch = 100000;
    opt.stratified = stratified;
    opt.seed = 5;
    const FormFactors ff = estimate_form_factors(ps, vis, opt);
    const double n = opt.rays_per_patch;
    const double opposite = test::parallel_rectangles(1, 1, 1), adjacent = test::perpendicular_rectangles(1, 1, 1);
    const double zc = z_critical(sidak(kAlpha, 30 + 15));
    test::ZTable table(std::string("unit cube F, stratified ") + (stratified ? "on" : "off"), zc);
    double max_z = 0, min_z_wrong = INFINITY;
    for (int i = 0; i < 6; ++i) {
      // Closed scene: no ray escapes or meets a back face, so the row sums to 1 up to float rounding.
      INFO("stratified " << stratified << ", row " << i << ": escaped " << ff.escaped[i] << ", back hits "
                         << ff.back_hits[i] << ", row sum " << ff.F.row(i).sum() << ", F_ii " << entry(ff.F, i, i));
      CHECK(ff.escaped[i] == 0);
      CHECK(ff.back_hits[i] == 0);
      CHECK(std::abs(double(ff.F.row(i).sum()) - 1) <= 6 * 0x1p-24);
      CHECK(entry(ff.F, i, i) == 0);
      for (int j = 0; j < 6; ++j) {
        if (j == i) continue;
        const double exact = (j / 2 == i / 2) ? opposite : adjacent;
        const double z = z_score(entry(ff.F, i, j), exact, n);
        max_z = std::max(max_z, std::abs(z));
        const std::string ij = std::to_string(i) + "," + std::to_string(j);
        table.add("F(" + ij + ")", entry(ff.F, i, j), test::binomial_se(entry(ff.F, i, j), n), exact);
        if (j / 2 == i / 2) min_z_wrong = std::min(min_z_wrong, std::abs(z_score(entry(ff.F, i, j), 0.19, n)));
        if (j > i) {
          // Reciprocity (all areas 1): F_ij - F_ji against its standard error (rows are independent).
          const double fij = entry(ff.F, i, j), fji = entry(ff.F, j, i);
          const double se = std::sqrt((fij * (1 - fij) + fji * (1 - fji)) / n);
          table.add("reciprocity F(" + ij + ") - F(" + std::to_string(j) + "," + std::to_string(i) + ")", fij - fji,
                    se, 0.0);
        }
      }
    }
    table.check();
    std::printf("unit cube (stratified %d): largest |z| %.2f of critical %.2f; wrong value 0.19 gives |z| >= %.1f\n",
                stratified, max_z, zc, min_z_wrong);
    // The same check rejects a wrong reference: 0.19 instead of 0.199825 for opposite faces.
    CHECK(min_z_wrong > zc);
  }
}

TEST_CASE("subdivided cube with triangles: no leaks, face-to-face factors", "[formfactor]") {
  const int k = 4;
  const PatchSet ps = test::unit_cube_room(k, true);
  const EmbreeVisibility vis(ps);
  FormFactorOptions opt;
  opt.rays_per_patch = 4000;
  // Equal rays per unit area, so face aggregates are plain ray fractions.
  opt.rays_per_area = 4000.0 * k * k;
  opt.min_rays = 1;
  const FormFactors ff = estimate_form_factors(ps, vis, opt);
  // Face of each patch from its normal: 0..5 in the order x=0, x=1, y=0, y=1, z=0, z=1.
  std::vector<int> face(ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const Vec3& nrm = ps.normal[i];
    int axis = 0;
    nrm.cwiseAbs().maxCoeff(&axis);
    face[i] = 2 * axis + (nrm[axis] < 0 ? 1 : 0);
  }
  double counts[6][6] = {}, rays[6] = {};
  long escaped = 0, back = 0, self = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    escaped += ff.escaped[i];
    back += ff.back_hits[i];
    rays[face[i]] += ff.rays[i];
    for (SparseF::InnerIterator it(ff.F, Eigen::Index(i)); it; ++it) {
      counts[face[i]][face[it.index()]] += std::round(it.value() * ff.rays[i]);
      self += it.index() == Eigen::Index(i);
    }
  }
  INFO(ps.size() << " patches: escaped " << escaped << ", back hits " << back << ", self hits " << self);
  CHECK(escaped == 0);
  CHECK(back == 0);
  CHECK(self == 0);
  const double zc = z_critical(sidak(kAlpha, 36));
  test::ZTable table("face to face F", zc);
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) {
      const double exact =
          a == b ? 0.0 : (a / 2 == b / 2 ? test::parallel_rectangles(1, 1, 1) : test::perpendicular_rectangles(1, 1, 1));
      const double f = counts[a][b] / rays[a];
      INFO("face " << a << " -> " << b << ": " << f << " exact " << exact << " from " << rays[a] << " rays");
      if (a == b)
        CHECK(f == 0);
      else
        table.add("face " + std::to_string(a) + " -> " + std::to_string(b), f, test::binomial_se(f, rays[a]), exact);
    }
  table.check();
}

TEST_CASE("F is bit-identical for 1 and 2 threads", "[formfactor]") {
  const PatchSet ps = test::unit_cube_room(3, true);
  const EmbreeVisibility vis(ps);
  FormFactorOptions opt;
  opt.rays_per_patch = 3000;
  auto run = [&](int threads) {
    ThreadLimit limit(threads);
    return estimate_form_factors(ps, vis, opt);
  };
  const FormFactors one = run(1), two = run(2);
  REQUIRE(one.F.nonZeros() == two.F.nonZeros());
  const auto nnz = std::size_t(one.F.nonZeros());
  CHECK(std::equal(one.F.valuePtr(), one.F.valuePtr() + nnz, two.F.valuePtr()));
  CHECK(std::equal(one.F.innerIndexPtr(), one.F.innerIndexPtr() + nnz, two.F.innerIndexPtr()));
  CHECK(std::equal(one.F.outerIndexPtr(), one.F.outerIndexPtr() + one.F.rows() + 1, two.F.outerIndexPtr()));
  CHECK(one.escaped == two.escaped);
  CHECK(one.back_hits == two.back_hits);
  // A different seed gives a different F (the seed is used).
  opt.seed = 2;
  const FormFactors other = run(2);
  CHECK(!(other.F.nonZeros() == one.F.nonZeros() &&
          std::equal(one.F.valuePtr(), one.F.valuePtr() + nnz, other.F.valuePtr())));
}

TEST_CASE("F is the same bit for bit whether the rows are traced in Morton or patch order, with 1 or 2 threads",
          "[formfactor]") {
  const PatchSet ps = test::unit_cube_room(6, true);  // 216 patches: the Morton order differs from patch order
  const EmbreeVisibility vis(ps);
  const std::vector<std::uint32_t> order = morton_order(ps.centroid, 0, ps.size());
  std::vector<std::uint32_t> identity(ps.size());
  std::iota(identity.begin(), identity.end(), 0u);
  REQUIRE(order != identity);
  FormFactorOptions opt;
  opt.rays_per_patch = 200;
  auto run = [&](bool morton, int threads) {
    ThreadLimit limit(threads);
    opt.morton_order = morton;
    return estimate_form_factors(ps, vis, opt);
  };
  const FormFactors reference = run(false, 1);
  for (const auto& [morton, threads] : {std::pair(true, 1), std::pair(true, 2), std::pair(false, 2)}) {
    INFO("morton " << morton << ", threads " << threads);
    const FormFactors f = run(morton, threads);
    REQUIRE(f.F.nonZeros() == reference.F.nonZeros());
    const auto nnz = std::size_t(f.F.nonZeros());
    CHECK(std::equal(f.F.valuePtr(), f.F.valuePtr() + nnz, reference.F.valuePtr()));
    CHECK(std::equal(f.F.innerIndexPtr(), f.F.innerIndexPtr() + nnz, reference.F.innerIndexPtr()));
    CHECK(std::equal(f.F.outerIndexPtr(), f.F.outerIndexPtr() + f.F.rows() + 1, reference.F.outerIndexPtr()));
    CHECK(f.escaped == reference.escaped);
    CHECK(f.back_hits == reference.back_hits);
  }
}

TEST_CASE("Morton order: codes interleave the quantised coordinates, the order sorts by them", "[formfactor]") {
  const Vec3 lo(0, 0, 0), hi(1, 1, 1);
  CHECK(morton_code(Vec3(0, 0, 0), lo, hi) == 0);
  CHECK(morton_code(Vec3(1, 0, 0), lo, hi) == spread_bits_by_3(0x1fffff));
  CHECK(morton_code(Vec3(0, 1, 0), lo, hi) == spread_bits_by_3(0x1fffff) << 1);
  CHECK(morton_code(Vec3(1, 1, 1), lo, hi) == (std::uint64_t(1) << 63) - 1);
  CHECK(spread_bits_by_3(0b101) == 0b1000001);
  // The four corners of a square in z = 0: (0,0), (1,0), (0,1), (1,1) in Z order, whatever their index order.
  const std::vector<Vec3> p = {{1, 1, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 0}};
  CHECK(morton_order(p, 0, 4) == std::vector<std::uint32_t>{3, 2, 1, 0});
  CHECK(morton_order(p, 1, 3) == std::vector<std::uint32_t>{2, 1});
}

TEST_CASE("back-face hits are counted when a patch faces the wrong way", "[formfactor]") {
  const PatchSet ps = parallel_squares(true);
  const EmbreeVisibility vis(ps);
  FormFactorOptions opt;
  opt.rays_per_patch = 100000;
  const FormFactors ff = estimate_form_factors(ps, vis, opt);
  const double exact = test::parallel_rectangles(1, 1, 1), n = opt.rays_per_patch;
  const double back = ff.back_hits[0] / n, zc = z_critical(sidak(kAlpha, 1));
  test::check_z("back-hit fraction", back, test::binomial_se(back, n), exact, zc);
  CHECK(ff.F.nonZeros() == 0);                   // nothing reaches a front face
  CHECK(ff.escaped[0] + ff.back_hits[0] == ff.rays[0]);
  CHECK(ff.escaped[1] == ff.rays[1]);             // patch 1 shoots away from patch 0
}

TEST_CASE("coaxial disks as 48-gons against the exact polygon value", "[formfactor]") {
  // Each disk (radius 1, distance 1) is a regular 48-gon cut into a fan of 48 equal triangles. The reference is
  // the exact view factor between the two polygons (contour integral); the disk value and the discretisation
  // error are printed for comparison only.
  const int sides = 48;
  const std::vector<Vec3> lower = regular_polygon(1, sides, 0, true), upper = regular_polygon(1, sides, 1, false);
  PatchBuilder b;
  const int m = b.add_material("white", Rgb(0.5, 0.5, 0.5));
  for (int k = 0; k < sides; ++k) b.add_triangle(Vec3(0, 0, 0), lower[k], lower[(k + 1) % sides], m);
  for (int k = 0; k < sides; ++k) b.add_triangle(Vec3(0, 0, 1), upper[k], upper[(k + 1) % sides], m);
  const PatchSet ps = b.build();
  const double polygon_area = 0.5 * sides * std::sin(2 * kPi / sides);
  const double exact = test::polygon_exchange_area(lower, upper) / polygon_area;
  const double disk = test::coaxial_disks(1, 1, 1);
  const EmbreeVisibility vis(ps);
  FormFactorOptions opt;
  opt.rays_per_patch = 8000;
  const FormFactors ff = estimate_form_factors(ps, vis, opt);
  double hits[2] = {0, 0}, rays[2] = {0, 0};
  for (int i = 0; i < 2 * sides; ++i) {
    rays[i / sides] += ff.rays[i];
    for (SparseF::InnerIterator it(ff.F, i); it; ++it)
      if (it.index() / sides != i / sides) hits[i / sides] += std::round(it.value() * ff.rays[i]);
  }
  const double zc = z_critical(sidak(kAlpha, 2));
  std::printf("coaxial 48-gons: exact polygon F %.6f, disk F %.6f (discretisation %.2e)\n", exact, disk, exact - disk);
  test::ZTable table("48-gon F", zc);
  for (int d = 0; d < 2; ++d) {
    const double f = hits[d] / rays[d];
    table.add("disk " + std::to_string(d), f, test::binomial_se(f, rays[d]), exact);
  }
  table.check();
  CHECK(std::abs(exact - disk) < 0.01);  // the 48-gon is close to the disk (area ratio 0.9971)
}

TEST_CASE("closed polyhedral sphere: rows sum to 1, entries match exact polygon values", "[formfactor]") {
  // Icosahedron subdivided twice, projected onto the unit sphere (320 triangles), normals inward. The faces are
  // inside the sphere, so F_ij is not A_j / A exactly: the reference for row i is the exact polygon value summed
  // over all faces sharing no corner with i (contour integral; the set S_i), which must match sum_{j in S_i} F_ij.
  std::vector<Vec3> v;
  std::vector<std::array<int, 3>> tri;
  const double t = (1 + std::sqrt(5.0)) / 2;
  for (const auto& p : {Vec3(-1, t, 0), Vec3(1, t, 0), Vec3(-1, -t, 0), Vec3(1, -t, 0), Vec3(0, -1, t), Vec3(0, 1, t),
                        Vec3(0, -1, -t), Vec3(0, 1, -t), Vec3(t, 0, -1), Vec3(t, 0, 1), Vec3(-t, 0, -1), Vec3(-t, 0, 1)})
    v.push_back(p.normalized());
  tri = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
         {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
         {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int level = 0; level < 2; ++level) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      return mid[key] = int(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& f : tri) {
      const int ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
      next.push_back({f[0], ab, ca});
      next.push_back({f[1], bc, ab});
      next.push_back({f[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    tri = next;
  }
  PatchBuilder b;
  const int m = b.add_material("white", Rgb(0.5, 0.5, 0.5));
  for (const auto& f : tri) b.add_triangle(v[f[0]], v[f[2]], v[f[1]], m);  // reversed: normals inward
  const PatchSet ps = b.build();
  REQUIRE(ps.size() == 320);
  REQUIRE(ps.normal[0].dot(ps.centroid[0]) < 0);

  const EmbreeVisibility vis(ps);
  FormFactorOptions opt;
  opt.rays_per_patch = 50000;
  const FormFactors ff = estimate_form_factors(ps, vis, opt);
  long escaped = 0, back = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    escaped += ff.escaped[i];
    back += ff.back_hits[i];
  }
  INFO("escaped " << escaped << ", back hits " << back << " of " << 320 * opt.rays_per_patch);
  CHECK(escaped == 0);
  CHECK(back == 0);

  const std::vector<int> rows = {0, 57, 160, 311};
  const double zc = z_critical(sidak(kAlpha, rows.size()));
  const double total_area = ps.total_area();
  test::ZTable table("sum over S_i of F", zc);
  for (int i : rows) {
    const std::vector<Vec3> pi = {ps.corner(i, 0), ps.corner(i, 1), ps.corner(i, 2)};
    double exact = 0, estimate = 0, sphere_limit = 0;
    for (std::size_t j = 0; j < ps.size(); ++j) {
      bool shares = false;
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) shares |= (ps.corner(i, a) - ps.corner(j, c)).norm() < 1e-12;
      if (shares) continue;
      const std::vector<Vec3> pj = {ps.corner(j, 0), ps.corner(j, 1), ps.corner(j, 2)};
      exact += test::polygon_exchange_area(pi, pj, 1, 12) / ps.area[i];
      estimate += entry(ff.F, i, int(j));
      sphere_limit += ps.area[j] / total_area;
    }
    const double z = z_score(estimate, exact, opt.rays_per_patch);
    std::printf("sphere row %d: sum over S_i of F: estimate %.5f, exact polygon %.5f, A_S/A %.5f, z %.2f\n", i,
                estimate, exact, sphere_limit, z);
    table.add("row " + std::to_string(i), estimate, test::binomial_se(estimate, opt.rays_per_patch), exact);
  }
  table.check();
}

TEST_CASE("rays per area and bad options", "[formfactor]") {
  FormFactorOptions opt;
  opt.rays_per_area = 100;
  opt.min_rays = 16;
  CHECK(ray_count(opt, 0.05) == 16);
  CHECK(ray_count(opt, 2.004) == 200);
  opt.rays_per_area = 0;
  CHECK(ray_count(opt, 2.0) == 1000);
  const PatchSet ps = test::unit_cube_room(1);
  const EmbreeVisibility vis(ps);
  FormFactorOptions bad;
  bad.rays_per_patch = 0;
  CHECK_THROWS_AS(estimate_form_factors(ps, vis, bad), InputError);
  bad = {};
  bad.rays_per_area = -1;
  CHECK_THROWS_AS(estimate_form_factors(ps, vis, bad), InputError);
  bad.rays_per_area = NAN;
  CHECK_THROWS_AS(estimate_form_factors(ps, vis, bad), InputError);
  bad = {};
  bad.min_rays = 0;
  CHECK_THROWS_AS(estimate_form_factors(ps, vis, bad), InputError);
  bad = {};
  bad.rays_per_area = 1e12;
  CHECK_THROWS_AS(estimate_form_factors(ps, vis, bad), InputError);
}
