#pragma once
// Bsdf: one of the scattering models radwalk renders, chosen per material, evaluated in the local shading frame.
//
// Contract of every model (lambertian.h, mirror.h, dielectric.h, conductor.h, microfacet.h):
//   f(wo, wi)   the BSDF value (1/sr); 0 for delta lobes,
//   pdf(wo, wi) the solid-angle density with which sample() returns wi; 0 for delta lobes,
//   sample(wo, u1, u2, uc) a direction wi with weight f |cos(wi)| / pdf, or nullopt (the path ends).
// Directions point away from the surface, +z is the normal. Every model except the dielectric is opaque
// (is_opaque()): it scatters only on the side wo.z() > 0, the front of the patch hit; a path reaching the back of
// a one-sided face is absorbed by the caller, and a two-sided face's back is a patch of its own
// (patch/patch_set.h, "Sides"). The dielectric is an interface: it scatters from both sides of its front normal.
// Reflectance never exceeds 1 per channel.
//
// Materials (mesh/material.h) map to models as follows (make_bsdf):
//   diffuse     -> Lambertian(R = rho)                       (rho = the patch's Kd)
//   mirror      -> Mirror(R = Ks, or 1 when Ks = 0)
//   dielectric  -> Dielectric(eta = Ni)
//   conductor   -> F0 = Ks (Kd when Ks = 0), index from F0 (fresnel.h); roughness alpha < 1e-3: smooth Conductor,
//                  else MicrofacetConductor(alpha)
//   microfacet  -> MicrofacetConductor(alpha = max(roughness, 1e-3)) with F0 as for conductor.
#include <optional>
#include <variant>

#include "mesh/material.h"
#include "pathtrace/conductor.h"
#include "pathtrace/dielectric.h"
#include "pathtrace/lambertian.h"
#include "pathtrace/microfacet.h"
#include "pathtrace/mirror.h"

namespace radwalk {

struct PatchSet;

class Bsdf {
 public:
  using Model = std::variant<Lambertian, Mirror, Dielectric, Conductor, MicrofacetConductor>;
  explicit Bsdf(Model model) : model_(std::move(model)) {}

  Rgb f(const Vec3& wo, const Vec3& wi) const {
    return std::visit([&](const auto& m) { return m.f(wo, wi); }, model_);
  }
  double pdf(const Vec3& wo, const Vec3& wi) const {
    return std::visit([&](const auto& m) { return m.pdf(wo, wi); }, model_);
  }
  std::optional<BsdfSample> sample(const Vec3& wo, double u1, double u2, double uc) const {
    return std::visit([&](const auto& m) { return m.sample(wo, u1, u2, uc); }, model_);
  }
  // Only delta lobes: next-event estimation is pointless and emission is always counted after it.
  bool is_delta() const {
    return std::holds_alternative<Mirror>(model_) || std::holds_alternative<Dielectric>(model_) ||
           std::holds_alternative<Conductor>(model_);
  }
  bool is_opaque() const { return !std::holds_alternative<Dielectric>(model_); }
  bool is_diffuse() const { return std::holds_alternative<Lambertian>(model_); }
  const Model& model() const { return model_; }

 private:
  Model model_;
};

// The model for material m on a patch with diffuse reflectance rho (see the table above).
Bsdf make_bsdf(const Material& m, const Rgb& rho);

// True when every material the patches use is diffuse: only then do the radiosity solvers apply.
bool is_diffuse_scene(const PatchSet& patches);

}  // namespace radwalk
