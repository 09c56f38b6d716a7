#include "pathtrace/bsdf.h"

#include <algorithm>

#include "patch/patch_set.h"
#include "pathtrace/fresnel.h"

namespace radwalk {

namespace {
constexpr double kSmoothAlpha = 1e-3;

Rgb specular_f0(const Material& m, const Rgb& rho) { return (m.Ks > 0).any() ? m.Ks : rho; }
}  // namespace

Bsdf make_bsdf(const Material& m, const Rgb& rho) {
  switch (m.kind) {
    case BsdfKind::diffuse:
      return Bsdf(Lambertian(rho));
    case BsdfKind::mirror:
      return Bsdf(Mirror((m.Ks > 0).any() ? m.Ks : Rgb(Rgb::Ones())));
    case BsdfKind::dielectric:
      return Bsdf(Dielectric(m.Ni));
    case BsdfKind::conductor: {
      const ConductorIor ior = conductor_ior_from_f0(specular_f0(m, rho));
      if (m.roughness < kSmoothAlpha) return Bsdf(Conductor(ior.eta, ior.k));
      return Bsdf(MicrofacetConductor(m.roughness, ior.eta, ior.k));
    }
    case BsdfKind::microfacet: {
      const ConductorIor ior = conductor_ior_from_f0(specular_f0(m, rho));
      return Bsdf(MicrofacetConductor(std::max(m.roughness, kSmoothAlpha), ior.eta, ior.k));
    }
  }
  return Bsdf(Lambertian(rho));
}

bool is_diffuse_scene(const PatchSet& patches) {
  return std::all_of(patches.material.begin(), patches.material.end(), [&](std::int32_t k) {
    return k < 0 || static_cast<std::size_t>(k) >= patches.materials.size() ||
           patches.materials[k].kind == BsdfKind::diffuse;
  });
}

}  // namespace radwalk
