#pragma once
// Light tracing on patches: particles shot from the emitters, tallied where they land. The continuous
// counterpart of progressive-refinement shooting; estimates the same patch-average radiosity as
// patch_average.h:
//   B_i = E_i + rho_i Phi_in,i / A_i,     Phi_in,i = flux arriving on the front of patch i (W).
// A particle leaves emitter j (chosen with probability P_j proportional to power A_j mean(E_j)) at a uniform
// point, in a cosine-distributed direction about the front normal, carrying flux w = A_j E_j / P_j (per
// channel), so E[sum of w over arrivals at i] = Phi_in,i. Each front arrival at i scores rho_i w / A_i; the
// particle then scatters by the patch's BSDF (w *= f |cos| / pdf) and, after rr_depth bounces, survives
// Russian roulette with probability q = min(1, max channel of w / w_emitted), w /= q (unbiased).
// Per-particle scores give the per-particle variance var and B_se = sqrt(var / particles).
// Depth cap: max_depth > 0 keeps at most max_depth reflections (as PathIntegrator: paths of at most max_depth
// scattering events), a bias.
// Random streams: particle k uses the stream (seed, light_particle, 0, k) (core/rng.h); bit-identical for any thread count.
//
// Image by light tracing (light_trace_image): every particle vertex y with a non-delta BSDF (and the emission
// point itself) is connected to the pinhole by a shadow ray and splatted into the pixel it projects to:
//   I_pixel += w f(y, wo, w_c) |cos(theta_y)| cos(theta_c) W(w_c) / |y - c|^2,     W = camera importance,
// and w f is replaced by w0 / pi at the emission point (Le = E / pi). Estimates the same pixel values as
// render_image (mean radiance over the pixel) with se from per-particle scores; RenderResult::spp holds the
// particle count. Paths through delta lobes only cannot reach a pinhole this way (they appear black).
#include <cstdint>

#include "pathtrace/camera.h"
#include "pathtrace/integrator.h"
#include "pathtrace/render.h"
#include "core/solution.h"

namespace radwalk {

struct LightTraceOptions {
  long particles = 1000000;  // >= 2
  std::uint64_t seed = 1;
  int rr_depth = 3;   // Russian roulette from this many bounces on
  int max_depth = 0;  // 0: unbounded; > 0: at most this many bounces (biased)
  bool progress = true;
};

// Solution::method = "lighttrace", walks = particles, steps = bounces; info: "rays", "escapes" (rays that hit nothing), "rays_per_second".
// A scene without emitters gives B = E = 0 with zero error. Throws InputError when particles < 2.
Solution light_trace_patches(const PatchSet& patches, const Visibility& visibility,
                             const LightTraceOptions& options);
// The same on the surfaces `geometry` describes (visibility must trace the same surfaces).
Solution light_trace_patches(const PatchSet& patches, const SurfaceGeometry& geometry, const Visibility& visibility,
                             const LightTraceOptions& options);

RenderResult light_trace_image(const PatchSet& patches, const Visibility& visibility, const Camera& camera,
                               int width, int height, const LightTraceOptions& options);

}  // namespace radwalk
