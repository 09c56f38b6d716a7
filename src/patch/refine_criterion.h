#pragma once
// The refinement criterion of adaptive patching: how much a patch's radiosity differs from its neighbours'.
//
// Compared quantity: the irradiance H_ic = max(0, B_ic - E_ic) / rho_ic (W/m^2, defined where rho_ic > 0), as the
// reflected radiosity it gives: for every edge-neighbour pair (i, j) (edge_neighbours: same plane, sharing all or
// part of an edge) and every channel c with rho_ic > 0 and rho_jc > 0, with rho*_c = max(rho_ic, rho_jc),
//     d_ijc = rho*_c |H_ic - H_jc| / max(rho*_c H_ic, rho*_c H_jc, floor_c),   0 when H_ic = H_jc,
// floor_c = floor_fraction x (area-weighted mean of B_c - E_c over all patches).
// For two non-emitting patches of the same material d_ijc is the relative difference of B (floor aside).
// Comparing H rather than B, nothing jumps where only the material changes (a light set into a ceiling, a
// checkerboard), where splitting would not help. The floor sets what counts: floor_fraction 0.01 makes d a
// relative difference everywhere but in the darkest corners; floor_fraction 1 makes it about an absolute
// difference in units of the scene's mean reflected radiosity (dark regions and dark materials split less), which
// suits an area-weighted (L2) error.
// jump_i = max over i's neighbours j and channels c of d_ijc, in [0, 1]. A patch without any coplanar edge
// neighbour (a block's side left as one quad, an isolated facet) cannot be judged this way: jump_i = 1, the largest
// possible value, so it is split until its children can be compared with each other.
// Noise: with Monte Carlo form factors, neighbours differ by noise alone. When the standard errors H_se of H are
// given, a difference counts only if it is also significant: |H_ic - H_jc| > noise_z x sqrt(se_ic^2 + se_jc^2)
// (otherwise d_ijc = 0; the pair still counts as judged).
// A patch is marked for splitting when jump_i > tol; both patches of a pair that differs are marked.
#include <utility>
#include <vector>

#include "core/types.h"
#include "patch/patch_set.h"

namespace radwalk {

// Defaults measured on the Cornell box (docs/experiments.md, "Adaptive patching"): floor 1 (an absolute
// difference against the mean reflected radiosity) gave a lower L2 error per patch than 0.01; the noise test is
// off because the binomial standard error overestimates the noise of stratified form factors several times.
inline constexpr double kDefaultRefineFloorFraction = 1;

inline constexpr double kDefaultRefineNoiseZ = 0;

struct JumpOptions {
  double floor_fraction = kDefaultRefineFloorFraction;  // >= 0
  PatchRgb H_se;                                        // N x 3 standard errors of H, or empty: no noise test
  double noise_z = kDefaultRefineNoiseZ;                // >= 0
  std::vector<double> visible;                          // N fractions in [0, 1], or empty: all 1
};

// Visible fraction v_i: the part of patch i not hidden inside a closed object (the floor under a block). The
// hidden part receives no light, so H_i / v_i is the irradiance of the visible part, and that is what is
// compared (H_se scales alike); otherwise the patches along a contact line would look darker than their
// neighbours at every size and split without bound. A patch with v_i = 0 is ignored: jump 0, its pairs skipped
// (a patch whose only neighbours are ignored gets jump 0, not 1). B: N x 3.
// Throws InputError if a visible fraction is outside [0, 1], floor_fraction < 0 or noise_z < 0; B, H_se and
// visible of the wrong size and a neighbour index out of range are InternalError (RADWALK_CHECK).
std::vector<double> radiosity_jumps(const PatchSet& patches, const PatchRgb& B,
                                    const std::vector<std::pair<PatchIndex, PatchIndex>>& neighbours,
                                    const JumpOptions& options = {});

// marked[i] = jump[i] > tol.
std::vector<bool> mark_jumps(const std::vector<double>& jump, double tol);

}  // namespace radwalk
