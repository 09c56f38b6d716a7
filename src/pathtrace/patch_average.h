#pragma once
// Patch-average radiosity by path tracing: the continuous counterpart of the radiosity solvers' B.
//
//   B_i = E_i + rho_i * (1/A_i) int_{A_i} E_irr(x) dx,     E_irr(x) = int_{H^2(n_i)} L_in(x, w) cos(theta) dw,
// in W/m^2 (radiosity; a Lambertian patch's outgoing radiance is B_i / pi). One sample of patch i takes x
// uniform on the patch (pdf 1/A_i, SurfaceGeometry::sample_point) and estimates E_irr(x) with PathIntegrator::irradiance
// (a cosine-sampled direction scores pi L_in; NEE/MIS add light samples), so Y = E_i + rho_i E_irr_hat(x) has
// mean B_i. The Solution gives B (mean of spp samples), var (per-sample variance, unbiased),
// B_se = sqrt(var / spp) and vov (the variance of the variance, core/moments.h CentralMoments4) per patch and channel.
// B_se is the sample standard deviation of the mean, honest only once the samples' tail is sampled: where rare paths
// carry much of the variance (a small bright reflector seen by few directions) it understates the error, and vov
// above kVovReliable says so (docs/path-tracer.md, "How far to trust B_se").
//
// Random streams: sample s of patch i uses the stream (seed, patch_average, i, s) (core/rng.h); the result is bit-identical for any thread count.
// rho_i is the patch's Kd whatever its material: on non-diffuse scenes (is_diffuse_scene false) the paths still
// follow the materials, but B has its radiosity meaning only on diffuse patches.
#include <cstdint>

#include "pathtrace/integrator.h"
#include "core/solution.h"

namespace radwalk {

struct PatchAverageOptions {
  long spp = 256;             // samples per patch
  std::uint64_t seed = 1;
  IntegratorOptions integrator;
  bool progress = true;       // core/progress.h
};

// Solution::method = "pathtrace-<integrator>", walks = samples, steps = scattering events,
// info: "rays", "escapes" (path rays that hit nothing), "spp", "rays_per_second", "rr_depth", "max_depth". Throws InputError when spp < 2.
Solution estimate_patch_averages(const PatchSet& patches, const Visibility& visibility,
                                 const PatchAverageOptions& options);
// The same on the surfaces `geometry` describes (visibility must trace the same surfaces).
Solution estimate_patch_averages(const PatchSet& patches, const SurfaceGeometry& geometry,
                                 const Visibility& visibility, const PatchAverageOptions& options);

}  // namespace radwalk
