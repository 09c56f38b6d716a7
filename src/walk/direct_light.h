#pragma once
// The first bounce of light from the emitters, D = diag(rho) F E, estimated by shadow rays with randomised Sobol
// points (ray geometry) or computed from a stored F (matrix kernel): the part of B that the Sobol shooting
// (random_walk_solver.h, WalkSampler::sobol with direct_light) takes out of the particles' work.
//
// Ray geometry, receiving patch j (rho_j > 0), M samples s = 0 .. M-1 of one replicate r:
//   D_j = rho_j (1 / A_j) sum_e E_e int_{A_j} int_{A_e} G(x, y) V(x, y) dy dx,
//   G = cos_x cos_y / (pi |y - x|^2) (both cosines > 0, else 0), V = 1 when the shadow ray from x towards y meets
//   nothing before y.
// Sample s: Sobol point s of core/sobol.h shifted by the words of stream (seed, direct_light_shift, j, r); x on j
// from (u0, u1) as sample_patch_point; the emitter e from u2 by inverse CDF over the emitted powers
// Phi_e = A_e sum_c E_ec (u2 rescaled to [0, 1) within e's interval), y on e from (u2', u3). The estimate is
//   D_j ~ rho_j (1/M) sum_s E_e G V A_e Phi / Phi_e,
// unbiased for D_j (each shifted point is uniform), with the error of a stratified (Sobol) rule. A shadow ray is
// traced only where both cosines are positive; it leaves x by spawn_ray (ray_offset.h) and V = 1 when its first
// hit is at t >= |y - x| (1 - 1e-5) - 4 eps (y itself, up to rounding) or nothing (a ray slipping between two
// emitter patches' shared edge).
// Matrix kernel (F stored): D = rho .* (F E) exactly, no rays.
//
// Exact where unoccluded (estimate_visible_direct_light, what --direct-light uses on the ray kernel unless
// WalkOptions::direct_sampled): D_j = rho_j sum_e E_e F_je with each F_je from formfactor/visible_form_factor.h
// (Lambert's point-to-polygon form factor at Sobol points of j, one shadow ray per point correcting for
// occlusion; docs/theory/point_polygon_form_factor.md). The M samples of receiver j are split evenly over the
// emitters it may see (patch_may_see), at least 1 each; emitter rank k of replicate r takes the shift of stream
// (seed, visible_direct_light, j, r << 32 | k). Unbiased; zero variance on a receiver that sees every emitter
// whole, so the noise is left in penumbrae and a receiver next to an emitter has no singularity. A receiver in
// full shadow gets 0 in expectation only, so D_j may come out slightly negative there (the shooting sources
// take |D|, stratified_emission.h).
#include "core/types.h"
#include "patch/patch_set.h"
#include "solve/problem.h"
#include "visibility/visibility.h"

namespace radwalk {

struct DirectLight {
  PatchRgb D;      // N x 3
  long rays = 0;   // shadow rays traced
};

// The ray-geometry estimate above, M = samples_per_patch (>= 1) per receiving patch, replicate r; patches run in
// parallel, the result independent of the thread count.
DirectLight estimate_direct_light(const RadiosityProblem& problem, const PatchSet& patches,
                                  const Visibility& visibility, long samples_per_patch, std::uint64_t seed,
                                  std::uint64_t replicate);

// The estimate exact where unoccluded, above: M = samples_per_patch (>= 1) per receiving patch, replicate r;
// patches run in parallel, the result independent of the thread count.
DirectLight estimate_visible_direct_light(const RadiosityProblem& problem, const PatchSet& patches,
                                          const Visibility& visibility, long samples_per_patch, std::uint64_t seed,
                                          std::uint64_t replicate);

// D = rho .* (F E) from problem.F (N x N).
PatchRgb exact_direct_light(const RadiosityProblem& problem);

}  // namespace radwalk
