// Discrete distribution and light sampler: samples against their probabilities (chi-square), inverses.
#include <catch2/catch.hpp>
#include <vector>

#include "core/discrete_distribution.h"
#include "core/error.h"
#include "core/rng.h"
#include "patch/patch_builder.h"
#include "pathtrace/facet_geometry.h"
#include "pathtrace/light_sampler.h"
#include "support/stat_checks.h"

using namespace radwalk;

TEST_CASE("discrete distribution: pmf, inverse round trip, chi-square", "[samplers][statistical]") {
  const std::vector<double> w = {1.0, 0.0, 3.0, 0.5, 0.0, 2.5};
  const DiscreteDistribution d(w);
  CHECK(d.total() == Approx(7.0));
  for (std::size_t k = 0; k < w.size(); ++k) {
    CHECK(d.pmf(k) == Approx(w[k] / 7.0));
    const auto [lo, hi] = d.inverse(k);
    CHECK(hi - lo == Approx(d.pmf(k)).margin(1e-15));
    if (d.pmf(k) > 0) {
      // Every u in the inverse interval maps back to k, and the remapped u is uniform on [0, 1).
      for (double t : {0.0, 0.25, 0.999}) {
        double r = -1;
        CHECK(d.sample(lo + t * (hi - lo), &r) == k);
        CHECK(r == Approx(t).margin(1e-9));
      }
    }
  }
  CHECK(d.pmf(d.sample(0x1.fffffffffffffp-1)) > 0);
  CHECK_THROWS_AS(DiscreteDistribution(std::vector<double>{0.0, 0.0}), InputError);
  CHECK_THROWS_AS(DiscreteDistribution(std::vector<double>{1.0, -1.0}), InputError);

  // H0: counts follow the pmf; alpha = 1e-3 (one test).
  const int n = 100000;
  std::vector<double> obs(w.size(), 0), exp(w.size(), 0);
  Rng rng = stream(61, StreamDomain::test, 0);
  for (int s = 0; s < n; ++s) obs[d.sample(rng.uniform())] += 1;
  for (std::size_t k = 0; k < w.size(); ++k) exp[k] = n * d.pmf(k);
  CHECK(obs[1] == 0);
  CHECK(obs[4] == 0);
  test::check_chi_square("discrete distribution", obs, exp, 1e-3);
}

TEST_CASE("light sampler: emitters chosen by power or area, points on the chosen patch", "[samplers][statistical]") {
  PatchBuilder b;
  const int dark = b.add_material("dark", Rgb::Constant(0.5));
  const int lamp = b.add_material("lamp", Rgb::Constant(0.2), Rgb(1.0, 2.0, 3.0));
  const int dim = b.add_material("dim", Rgb::Zero(), Rgb(0.5, 0.0, 0.1));
  b.add_quad(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), dark);
  b.add_quad(Vec3(0, 0, 1), Vec3(0, 2, 1), Vec3(2, 2, 1), Vec3(2, 0, 1), lamp);  // area 4, mean E = 2 pi
  b.add_triangle(Vec3(0, 0, 2), Vec3(0, 1, 2), Vec3(1, 0, 2), dim);               // area 0.5, mean E = 0.2 pi
  const PatchSet p = b.build();

  const FacetGeometry facets(p);
  const LightSampler by_power(p, facets, LightSelection::power), by_area(p, facets, LightSelection::area);
  REQUIRE(by_power.emitters().size() == 2);
  const double pw1 = 4 * 2.0, pw2 = 0.5 * 0.2;
  CHECK(by_power.pmf(0) == 0);
  CHECK(by_power.pmf(1) == Approx(pw1 / (pw1 + pw2)));
  CHECK(by_power.pdf_area(2) == Approx(pw2 / (pw1 + pw2) / 0.5));
  CHECK(by_area.pmf(1) == Approx(4.0 / 4.5));
  CHECK((by_power.total_power() - kPi * (4.0 * Rgb(1, 2, 3) + 0.5 * Rgb(0.5, 0, 0.1))).abs().maxCoeff() < 1e-12);

  // H0: choices follow the pmf (alpha = 1e-3, Sidak over the 2 selections); points lie on the chosen patch.
  const double a = sidak(1e-3, 2);
  int seed = 0;
  for (const LightSampler* ls : {&by_power, &by_area}) {
    std::vector<double> obs(2, 0), exp = {0, 0};
    Rng rng = stream(71, StreamDomain::test, seed++);
    const int n = 50000;
    for (int s = 0; s < n; ++s) {
      const LightSample x = ls->sample(rng.uniform(), rng.uniform(), rng.uniform());
      REQUIRE((x.patch == 1 || x.patch == 2));
      REQUIRE(std::abs((x.point - p.centroid[x.patch]).dot(p.normal[x.patch])) < 1e-12);
      REQUIRE(x.pdf_area == Approx(ls->pdf_area(x.patch)));
      REQUIRE((x.Le - p.E[x.patch] / kPi).abs().maxCoeff() < 1e-15);
      obs[x.patch - 1] += 1;
    }
    exp[0] = n * ls->pmf(1);
    exp[1] = n * ls->pmf(2);
    test::check_chi_square(ls == &by_power ? "emitters by power" : "emitters by area", obs, exp, a);
  }
}
