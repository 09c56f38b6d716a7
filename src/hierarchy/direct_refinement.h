#pragma once
// The direct light of the elements, exact where unoccluded, and the tree refined where it fluctuates
// (docs/theory/hierarchical_radiosity.md, "The direct light and its oracle").
//
// Element e (input patch r, reflectance rho, area A_e) gets M = m^2 jittered points x_s (a stratified m x m grid of
// the unit square, one jitter each, mapped by element_point), and at each point the irradiance from the emitters
//   f_s = sum_k E_k [F(x_s -> k) - A_k G(x_s, y_sk) (1 - V(x_s, y_sk))],
// F(x -> k) Lambert's exact unoccluded point-to-polygon form factor (formfactor/point_polygon_form_factor.h), y_sk
// a uniform point of emitter k, G = cos_x cos_y / (pi r^2) (0 where y is outside x's hemisphere or behind k's
// front), V = 1 when the shadow ray from x_s to y_sk meets nothing before y_sk. E[A_k G (1 - V)] = int_k G (1 - V)
// = F - int_k G V, so f_s is unbiased for the visible point-to-polygon factor, exact wherever y_sk is visible (the
// estimator of solve/fluctuation_source.h). (F V, a first version, is biased wherever G varies over a partly hidden
// emitter, and most where k straddles x's plane: the uniform points behind the plane were sent into the
// receiver's own object and counted as hidden, which took up to half the light from the vertical sides of
// furniture under a ceiling light; the test `direct refinement: the direct light of a box's side under a light
// that straddles its plane is exact` shows it.) Then
//   D_e = rho mean_s f_s                         unbiased for the element average of rho sum_k E_k int_k G V,
//   var(D_e) <= rho^2 s^2 / M                    s^2 the sample variance of f_s (stratification only lowers it),
// and the oracle's indicator, the power that a constant value misplaces on e,
//   I_e = A_e max_c rho_c s_c,
// s_c here the spread over the points of h_s, the same visible factor with one emitter point y_k per emitter shared
// by all M points (common random numbers): in an umbra f_s = F - A G varies with its own random y_sk (noise, not a
// fluctuation of the light), while h_s varies only as G(x_s, y_k) does over the element; in a penumbra V(x_s, y_k)
// changes between the points. (2 shadow rays per point and emitter.)
// e is split when I_e > epsilon, level < max_level and A_e / 4 >= min_area; its children are estimated in turn.
// A shadow or penumbra boundary crossing e makes some f_s zero and others not, so s_c is of the order of f itself
// there, while lit regions far from the emitters vary smoothly and umbrae not at all: refinement follows the
// boundaries. A shadow smaller than the spacing of the points can fall between them all and be missed (the
// oracle sees no sample in it): M is the user's guard (--hierarchical-points).
// Work: level by level, the elements of a level in parallel (element e draws from stream (seed,
// hierarchical_direct, e, 0)), the splits done in element order: the tree and D do not depend on the thread count.
#include <cstdint>
#include <vector>

#include "hierarchy/element_tree.h"
#include "patch/patch_set.h"
#include "visibility/ray_offset.h"
#include "visibility/visibility.h"

namespace radwalk {

struct DirectRefinementOptions {
  double epsilon = 0;   // power threshold of the indicator I_e (W in the mesh's units)
  double min_area = 0;  // no child below this area
  int max_level = 10;
  int points_side = 4;  // m: M = m^2 points per element
  std::uint64_t seed = 1;
};

struct DirectRefinement {
  std::vector<Rgb> D;         // per element (tree.size()): rho mean f (0 for non-reflecting elements)
  std::vector<Rgb> variance;  // per element: rho^2 s^2 / M
  std::vector<double> indicator;  // per element: I_e
  long shadow_rays = 0;
  long splits = 0;
};

// Refines `tree` (whose leaves are the starting elements) in place and returns D at every element of the result.
// visibility: over the PatchSet `roots` the tree was made from.
DirectRefinement refine_direct_light(const PatchSet& roots, const Visibility& visibility, ElementTree& tree,
                                     const DirectRefinementOptions& options);

// The visible point-to-polygon factor from point x (normal n, on a patch whose shadow rays leave by `offset`) to
// emitter k, by one uniform point y of k: F - A_k G(x, y) (1 - V(x, y)) with F = F(x -> k) given (above); unbiased,
// and F itself wherever y is visible or G(x, y) = 0. Counts the shadow ray traced in `rays`.
double visible_point_form_factor(const PatchSet& roots, const Visibility& visibility, const PatchRayOffset& offset,
                                 const Vec3& x, const Vec3& n, std::size_t k, const Vec3& y, double F, double eps,
                                 long& rays);

// The emitters of a PatchSet: the patches with E > 0 in some channel, increasing.
std::vector<std::size_t> emitter_roots(const PatchSet& roots);

}  // namespace radwalk
