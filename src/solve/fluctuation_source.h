#pragma once
// The source term of the discretisation error of the piecewise-constant radiosity system: the within-patch
// fluctuation of the radiosity, shot to the patches that see it (derivation: docs/theory/discretisation_error.md).
//
// Averaging the continuous equation B(x) = E(x) + rho(x) int G(x, y) B(y) dy over patch i gives, for the patch
// averages Bbar_i = (1/A_i) int_i B,
//   Bbar = E + H Bbar + d,     d_i = rho_i (1/A_i) int_i int G(x, y) (B(y) - Bbar_{j(y)}) dy dx     (H = diag(rho) F),
// so the discrete solution B_h of B_h = E + H B_h is off by e = Bbar - B_h = (I - H)^{-1} d. d_i is how the
// fluctuation of the radiosity inside the patches that i sees correlates with where i sees them: 0 when every
// patch's radiosity is constant. By the symmetry of G, d is the fluctuation shot from each patch j:
//   d_k = rho_k (1/A_k) sum_j int_j (B(y) - Bbar_j) F(y -> k) dy,      F(y -> k): the point-to-patch form factor.
//
// The fluctuation is modelled by one gather of the discrete solution (E is constant per patch):
//   B(y) - Bbar_j ~ rho_j (g(y) - gbar_j),    g(y) = int B_h(hit(y, w)) cos / pi dw,
// and estimated per patch j (rho_j > 0) and replicate r = 0, 1 from M_j stratified points y_m of j (s_j x s_j strata;
// one density of points over the scene: s_j = s on a patch of the median area, round(s sqrt(A_j / A_median)) on a
// larger one, at most 8, so that the small regions where a large patch's radiosity departs from its mean, under an
// object or inside a shelf, are found as often as on small patches):
//   g_m = (1/L) sum_l (B_h - E)(hit(y_m, w_l))
//       + (1/L) sum_l E_e / p(e_l) [F(y_m -> e_l) - A_e G(y_m, z_l) (1 - V(y_m, z_l))],
// with L cosine directions w_l and L emitter points z_l (emitter e_l chosen by power, z_l uniform on it) shared by
// all the points (common random numbers: where the points see the same thing, their g agree exactly); F(y -> e)
// is the exact unoccluded point-to-polygon factor, so the emitted part has noise only where z is hidden; then
//   delta_m = rho_j (g_m - mean_m g_m) M / (M - 1)      (the sample-covariance correction of centring on M points),
// shot along L further cosine directions v_l shared by the points (L' in the near field, below): the patch k hit
// from y_m (front) gets
//   rho_k delta_m A_j / (A_k M L).
// Where all the points see the same patch the contributions cancel exactly (sum_m delta_m = 0), so only the near
// geometry adds noise.
//
// The near field. A patch k closer to j than the spacing h_j = sqrt(A_j) / s_j of j's points sees j through a
// point-to-patch factor F(y -> k) that varies within one stratum (near a shared corner it is largest within a few
// times k's distance of the edge), while the fluctuation there can be large (a floor beside the wall under a light:
// dark at the wall, bright a few mm out). Then whether one of j's s_j^2 points lands in the few mm that k sees
// decides d_k, and the estimate is right only on average: on the spot-lit room's 2.5 mm wall band under the light,
// four points a replicate on the 12.5 mm floor leaf beside it gave d = -0.43 +- 0.25 for a true -1.96 (the
// variance above is given the points and misses the points' own spread); and a thin patch k beside j is reached only
// by the shots of j's few points nearest to it, whose directions alone decide d_k (on the spot-lit room's 0.6 mm
// wall leaves in the floor's corner under the light, d = -1.7 +- 1.7 with L for a true -2.5, which the
// empirical-Bayes B_disc of discretisation_error.h shrinks to 0.2). So patch j first traces a pilot: L cosine rays
// from each of s_j x s_j stratified points and from s_j stratified points along each edge (a hair inside it: a thin
// neighbour across an edge is found wherever along the edge it lies), of a stream of its own. Its near targets T_j
// are the patches k (front, rho_k > 0) a pilot ray reaches within h_j that are thinner than h_j (width: area over
// longest edge). When there
// are any, both replicates use points spaced no wider than the thinnest target (n_j = ceil(sqrt(A_j) / w_min) per
// side, at most 16; streams of their own), shoot as above to every patch but the targets (a near-field patch is
// where the fluctuation is steep, and its many points keep the shots to the rest of the scene quiet too: from its
// own 2 x 2 points alone, the spot-lit room's hierarchy took up to 1.5 times the leaves for 1 %), and reach each
// target through the visible point-to-patch factor instead of shots:
//   d_k += rho_k delta_m A_j F_vis(y_m -> k) / (A_k (M - 1))      for k in T_j, M = n_j^2,
// F_vis = F(y -> k) - A_k G(y, z) (1 - V(y, z)) from one uniform point z of k (exact where nothing hides z), so
// neither the points' luck nor the directions' decide d_k. Unbiased as the shots are (the pilot chooses only the
// targets and the points' number, not the points). Replicate r's variance for a near target: the strata paired
// with a neighbour, M / (2 P) sum over the P pairs of their terms' squared difference (the collapsed-strata estimate
// of a stratified sum's variance), paired along each coordinate in turn and the smaller taken (the terms fall
// steeply toward the target; pairs along its edge see the least of that trend).
// d is the mean of the two replicates, and its variance the larger of two estimates:
//   (d_k^(0) - d_k^(1))^2 / 4                 (the replicates: every source of noise, but one degree of freedom),
//   (1/4) sum_{r, j, l} (sum_m shot_{j,m,l -> k}^(r))^2 (+ the near targets' terms)
//                                             (given the points, the L shot directions of a patch j are
//                                             independent; along one direction the points' shots to k are summed,
//                                             as they cancel where the points see the same place),
// so that a small patch whose d rests on a few large shots from a large patch is not, by a chance agreement of
// the two replicates, taken as known exactly. (Reaching the targets exactly replaced shooting along 4 L directions
// from the near field's points, which cost about twice the rays.)
//
// Rays per patch: 2 replicates x M_j points x (L gather + L shot cosine rays + L shadow rays when the scene has
// emitters), plus the pilot's (s_j^2 + c_j s_j) L (c_j the corners), plus with near targets |T_j| shadow rays per
// point (M_j = n_j^2 there).
// Reproducible: patch j draws from stream (seed, discretisation_estimate, j, r); the contributions are summed in
// patch order, independent of the thread count.
#include <cstdint>
#include <vector>

#include "core/types.h"
#include "formfactor/sparse_f.h"
#include "patch/patch_set.h"
#include "visibility/visibility.h"

namespace radwalk {

struct FluctuationSource {
  PatchRgb d;         // N x 3: the estimate of d_k (W per unit length squared, as B)
  PatchRgb replicate[2];  // N x 3 each: d^(0), d^(1), the two independent replicates (d = their mean)
  PatchRgb variance;  // N x 3: the variance of that estimate
  SparseF F;          // N x N: the shot rays' form factors (2 M_j L rays in row j), for scenes without a stored F
  std::vector<std::vector<Rgb>> deltas;  // per patch, delta_m of replicate r at r M_j + m (B / moment_scale(max
                                         // B)); only when asked (keep_deltas), for weighted_fluctuation_shots
  std::vector<std::vector<std::int32_t>> near_targets;  // per patch, T_j ascending (with keep_deltas)
  long shot_rays = 0;  // the rays weighted_fluctuation_shots traces again: the shots and the targets' shadow rays
  int points = 0;     // M per patch of the median area and replicate (more on larger patches, above)
  long near_field_patches = 0;  // patches with near targets (above)
  std::vector<int> sides;       // per patch: its points per side, n_j where it has near targets (0 where rho_j = 0)
  int directions = 0; // L
  long rays = 0;      // traced in all
};

// B: the discrete solution (N x 3, finite, >= 0). directions L >= 1; points M >= 2 on a patch of the median area
// (rounded up to a square; larger patches get more, above). near_field false: no near-field refinement (each patch
// its own s_j; for comparisons).
FluctuationSource fluctuation_source(const PatchSet& patches, const Visibility& visibility, const PatchRgb& B,
                                     int directions, std::uint64_t seed, int points = 4, bool keep_deltas = false,
                                     bool near_field = true);

// The shots of fluctuation_source weighted by the receivers, summed per shooter (docs/theory/discretisation_error.md,
// "Which patch causes the error: the shooter attribution"):
//   a_j = sum_r sum_{shots s of j in replicate r} sum_c w^(r)_{k(s) c} s_c,
// where s is one shot rho_k delta_m A_j / (A_k M L) of patch j to the patch k it hits, or one near target's share
// of replicate r (above) (the terms whose sum over j is
// d^(r)_k), and w^(r) (N x 3, finite) the receivers' weights for replicate r's shots. source: fluctuation_source of
// the same arguments with keep_deltas (checked): its delta_m are shot again along the same directions from the same
// points, and the near targets reached again through the same points of theirs (the same streams; the gathers are
// not traced again), so the shots are the same ones bit for bit and
// sum_j a_j = sum_r sum_{k,c} w^(r)_kc d^(r)_kc up to rounding. Patch j's sum is formed by j alone (its shots in
// their own order): reproducible for any thread count. Rays: the shot rays and the near targets' shadow rays
// (FluctuationSource::shot_rays).
std::vector<double> weighted_fluctuation_shots(const PatchSet& patches, const Visibility& visibility,
                                               const PatchRgb& B, const FluctuationSource& source,
                                               const PatchRgb (&weights)[2], int directions, std::uint64_t seed,
                                               int points = 4);

}  // namespace radwalk
