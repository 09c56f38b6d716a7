// BSDF models: white-furnace energy conservation, samplers against their pdfs (chi-square), weight/pdf
// consistency, reciprocity, and the material mapping. Statistical checks state their family-wise alpha.
#include <catch2/catch.hpp>
#include <cmath>

#include "core/moments.h"
#include "direction_bins.h"
#include "patch/patch_builder.h"
#include "pathtrace/bsdf.h"
#include "pathtrace/fresnel.h"
#include "support/stat_checks.h"

using namespace radwalk;
using radwalk::test::check_z;
using radwalk::test::uniform_sphere;

namespace {
Vec3 direction(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}
// F = 1 for every angle: a conductor with huge k.
MicrofacetConductor white_ggx(double alpha) { return MicrofacetConductor(alpha, Rgb::Ones(), Rgb::Constant(1e7)); }
}  // namespace

TEST_CASE("white furnace: a rho = 1 Lambertian reflects everything (uniform-sphere estimate)", "[bsdf][statistical]") {
  // H0: albedo = int f cos dwi = 1 for each of 3 wo; alpha = 1e-3 family-wise, Sidak over 3.
  const double z = z_critical(sidak(1e-3, 3));
  const Lambertian lambert(Rgb::Ones());
  int k = 0;
  for (double theta : {0.1, 0.8, 1.4}) {
    const Vec3 wo = direction(theta, 0.3);
    PowerSums m;
    Rng rng = stream(11, StreamDomain::test, k++);
    for (int s = 0; s < 200000; ++s) {
      const Vec3 wi = uniform_sphere(rng.uniform(), rng.uniform());
      m.add(lambert.f(wo, wi)[0] * std::abs(wi.z()) * 4 * kPi);
    }
    check_z("Lambertian albedo", m.mean(), m.standard_error(), 1.0, z);
  }
}

TEST_CASE("GGX: D is normalised and passes the weak white furnace test", "[bsdf][ggx][statistical]") {
  // H0 (Heitz 2014): int D(wm) cos(theta_m) dwm = 1 and int D(wh) G1(wo) / (4 cos(wo)) dwi = 1 over the whole
  // sphere of wi, for 2 alphas x 3 wo (weak furnace) + 2 (normalisation): 8 checks, alpha = 1e-3 family-wise.
  const double z = z_critical(sidak(1e-3, 8));
  int k = 0;
  for (double alpha : {0.2, 0.6}) {
    const Ggx ggx(alpha);
    PowerSums norm;
    Rng rng = stream(21, StreamDomain::test, k++);
    for (int s = 0; s < 400000; ++s) {
      const Vec3 wm = uniform_sphere(rng.uniform(), rng.uniform());
      norm.add(ggx.D(wm) * std::max(0.0, wm.z()) * 4 * kPi);
    }
    check_z("int D cos", norm.mean(), norm.standard_error(), 1.0, z);
    for (double theta : {0.0, 0.9, 1.45}) {
      const Vec3 wo = direction(theta, 1.1);
      PowerSums weak;
      Rng r2 = stream(22, StreamDomain::test, k++);
      for (int s = 0; s < 400000; ++s) {
        const Vec3 wi = uniform_sphere(r2.uniform(), r2.uniform());
        const Vec3 wh = (wo + wi).normalized();
        weak.add(ggx.D(wh) * ggx.G1(wo) / (4 * wo.z()) * 4 * kPi);
      }
      check_z("weak white furnace", weak.mean(), weak.standard_error(), 1.0, z);
    }
  }
}

TEST_CASE("samplers follow their pdfs (chi-square): Lambertian and GGX microfacet", "[bsdf][statistical]") {
  // 1 Lambertian + 2 alphas x 2 wo = 5 tests, alpha = 1e-3 family-wise.
  const double alpha_each = sidak(1e-3, 5);
  const Lambertian lambert(Rgb::Constant(0.5));
  const Vec3 wo0 = direction(0.5, 0.2);
  const test::BinCounts lambert_counts = test::direction_counts(
      [&](Rng& r, Vec3& w) {
        const auto s = lambert.sample(wo0, r.uniform(), r.uniform(), r.uniform());
        if (s) w = s->wi;
        return s.has_value();
      },
      [&](const Vec3& wi) { return lambert.pdf(wo0, wi); }, 200000, 31);
  test::check_chi_square("Lambertian sampler", lambert_counts.observed, lambert_counts.expected, alpha_each);
  std::uint64_t seed = 32;
  for (double alpha : {0.3, 0.7})
    for (double theta : {0.2, 1.2}) {
      const MicrofacetConductor mf(alpha, Rgb::Constant(1.5), Rgb::Constant(3.0));
      const Vec3 wo = direction(theta, 0.4);
      const test::BinCounts counts = test::direction_counts(
          [&](Rng& r, Vec3& w) {
            const auto s = mf.sample(wo, r.uniform(), r.uniform(), r.uniform());
            if (s) w = s->wi;
            return s.has_value();
          },
          [&](const Vec3& wi) { return mf.pdf(wo, wi); }, 300000, seed++);
      test::check_chi_square("GGX sampler, alpha " + std::to_string(alpha) + ", theta_o " + std::to_string(theta),
                             counts.observed, counts.expected, alpha_each);
    }
}

TEST_CASE("microfacet: sample weight equals f cos / pdf, f is reciprocal, albedo <= 1", "[bsdf][ggx][statistical]") {
  // Deterministic identities up to rounding; then H0 for each of 3 (alpha, wo): the mean sample weight
  // (importance-sampled albedo) equals the uniform-sphere estimate of int f cos (two-sample z-test), and the
  // albedo of an F = 1 surface is <= 1 (one-sided). 6 checks, alpha = 1e-3 family-wise.
  const double z = z_critical(sidak(1e-3, 6));
  int k = 0;
  for (double alpha : {0.1, 0.5, 0.9}) {
    const MicrofacetConductor mf = white_ggx(alpha);
    const Vec3 wo = direction(0.3 + alpha, 2.0);
    Rng rng = stream(41, StreamDomain::test, k++);
    PowerSums sampled, uniform;
    for (int s = 0; s < 200000; ++s) {
      const auto bs = mf.sample(wo, rng.uniform(), rng.uniform(), rng.uniform());
      if (bs) {
        const double via_f = mf.f(wo, bs->wi)[0] * bs->wi.z() / mf.pdf(wo, bs->wi);
        REQUIRE(bs->weight[0] == Approx(via_f).epsilon(1e-9));
        REQUIRE(bs->pdf == Approx(mf.pdf(wo, bs->wi)).epsilon(1e-9));
        REQUIRE(mf.f(wo, bs->wi)[1] == Approx(mf.f(bs->wi, wo)[1]).epsilon(1e-12));
      }
      sampled.add(bs ? bs->weight[0] : 0.0);
      const Vec3 wi = uniform_sphere(rng.uniform(), rng.uniform());
      uniform.add(mf.f(wo, wi)[0] * std::max(0.0, wi.z()) * 4 * kPi);
    }
    INFO("alpha " << alpha << ": sampled albedo " << sampled.mean() << " +- " << sampled.standard_error()
                  << ", uniform " << uniform.mean() << " +- " << uniform.standard_error());
    const double se_a = sampled.standard_error(), se_b = uniform.standard_error();
    check_z("importance-sampled vs uniform albedo", sampled.mean(), std::sqrt(se_a * se_a + se_b * se_b),
            uniform.mean(), z);
    CHECK(sampled.mean() - 1.0 < z * sampled.standard_error());
    // Single scattering loses energy, more with roughness: a loose physical sanity bound.
    CHECK(sampled.mean() > 0.5);
  }
}

TEST_CASE("delta lobes: mirror and conductor reflect with their reflectance, dielectric R + T = 1",
          "[bsdf][statistical]") {
  const Vec3 wo = direction(0.7, 0.5);
  const Mirror mirror(Rgb::Ones());
  const auto m = mirror.sample(wo, 0.3, 0.3, 0.3);
  REQUIRE(m);
  CHECK((m->wi - Vec3(-wo.x(), -wo.y(), wo.z())).norm() < 1e-15);
  CHECK((m->weight - 1.0).abs().maxCoeff() == 0.0);
  CHECK(m->delta);

  const ConductorIor ior = conductor_ior_from_f0(Rgb(0.9, 0.5, 0.2));
  const Conductor conductor(ior.eta, ior.k);
  const auto c = conductor.sample(wo, 0.1, 0.2, 0.3);
  REQUIRE(c);
  CHECK((c->weight - fresnel_conductor(wo.z(), ior.eta, ior.k)).abs().maxCoeff() < 1e-15);

  // Dielectric: each lobe has weight 1 and probability F resp. 1 - F (so the albedo R + T is exactly 1), and
  // the reflected fraction of samples estimates F: binomial z-test for 4 angles x 2 sides, alpha = 1e-3.
  const Dielectric glass(1.5);
  const double z = z_critical(sidak(1e-3, 8));
  int k = 0;
  for (double side : {1.0, -1.0})
    for (double theta : {0.0, 0.5, 0.7, 1.3}) {
      Vec3 w = direction(theta, 0.2);
      w.z() *= side;
      const double F = fresnel_dielectric(w.z(), 1.5);
      Rng rng = stream(51, StreamDomain::test, k++);
      PowerSums reflected;
      for (int s = 0; s < 100000; ++s) {
        const auto bs = glass.sample(w, rng.uniform(), rng.uniform(), rng.uniform());
        REQUIRE(bs);
        REQUIRE((bs->weight - 1.0).abs().maxCoeff() == 0.0);
        const bool refl = bs->wi.z() * w.z() > 0;
        REQUIRE(bs->pdf == Approx(refl ? F : 1.0 - F));
        reflected.add(refl ? 1.0 : 0.0);
      }
      INFO("side " << side << ", theta " << theta << ", F " << F);
      if (F < 1.0) {
        check_z("reflected fraction", reflected.mean(), std::sqrt(F * (1 - F) / reflected.n), F, z);
      } else {
        CHECK(reflected.mean() == 1.0);  // total internal reflection
      }
    }
}

TEST_CASE("materials map to models, is_diffuse_scene", "[bsdf]") {
  Material m;
  m.Kd = Rgb(0.5, 0.4, 0.3);
  CHECK(make_bsdf(m, m.Kd).is_diffuse());
  m.kind = BsdfKind::mirror;
  CHECK(std::holds_alternative<Mirror>(make_bsdf(m, m.Kd).model()));
  m.kind = BsdfKind::dielectric;
  CHECK_FALSE(make_bsdf(m, m.Kd).is_opaque());
  m.kind = BsdfKind::conductor;
  CHECK(std::holds_alternative<Conductor>(make_bsdf(m, m.Kd).model()));
  m.roughness = 0.3;
  CHECK(std::holds_alternative<MicrofacetConductor>(make_bsdf(m, m.Kd).model()));

  PatchBuilder b;
  const int white = b.add_material("white", Rgb::Constant(0.5));
  b.add_triangle(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), white);
  CHECK(is_diffuse_scene(b.build()));
  Material mirror;
  mirror.kind = BsdfKind::mirror;
  b.add_triangle(Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1), b.add_material(mirror));
  CHECK_FALSE(is_diffuse_scene(b.build()));
}
