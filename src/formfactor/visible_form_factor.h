#pragma once
// The form factor from a patch to a (small, bright) patch with the unoccluded part exact: the point-to-polygon
// form factor (point_polygon_form_factor.h) times a visibility correction by shadow rays, integrated over the
// receiving patch at randomised Sobol points (docs/theory/point_polygon_form_factor.md, "Visibility").
//
//   F_ie = (1 / A_i) int_{A_i} int_{A_e} G(x, y) V(x, y) dy dx,   G = cos_x cos_y / (pi |y - x|^2) (0 unless both
//   cosines are positive), V = 1 when the segment x -> y is unoccluded.
// With F(x -> e) = int_{A_e} G(x, y) dy (exact, Lambert), int_{A_e} G V dy = F(x -> e) - int_{A_e} G (1 - V) dy,
// and the second integral is estimated by one uniform point y on e per point x (a control variate with the
// known mean F(x -> e)). Sample s = 0 .. M-1 takes Sobol point s (core/sobol.h) with the caller's digital shift:
// x on i from (u0, u1), y on e from (u2, u3) (sample_patch_point's warp), and scores
//   f_s = F(x -> e) - A_e G(x, y) (1 - V(x, y)),          F_ie ~ (1 / M) sum_s f_s.
// Unbiased (each shifted point is uniform on [0, 1)^4); exact (zero variance) where every x of i sees all of e,
// so the noise is confined to penumbrae and there is no 1 / r^2 singularity next to the emitter (the shadow-ray
// point-to-point estimator A_e G V has infinite variance on a receiver sharing an edge with e). A sample whose
// segment is blocked scores F(x -> e) - A_e G, which may be negative: in full shadow the estimate is 0 only in
// expectation, so single estimates of a shadowed entry can be slightly negative.
// A shadow ray is traced only where G > 0, from spawn_ray (visibility/ray_offset.h), as an occlusion query with
// tmax = t_e (1 - 1e-5) - 4 eps, t_e = min(|y - x|, distance from the ray's (offset) origin along the ray to e's
// plane): it stops short of e's plane up to rounding, so e itself (or a coplanar neighbour) never blocks it, also
// at grazing angles where the origin offset brings that plane nearer than |y - x|.
#include <cstddef>
#include <vector>

#include "core/sobol.h"
#include "patch/patch_set.h"
#include "visibility/visibility.h"

namespace radwalk {

class VisibleFormFactor {
 public:
  // Keeps references: the patches and the visibility must outlive this object.
  VisibleFormFactor(const PatchSet& patches, const Visibility& visibility);

  // The estimate above of F_ie from M >= 1 samples with the given shift, for receiving patch i (its normal the
  // cos_x side) and target patch e != i. Adds the shadow rays traced to `rays`. Thread-safe (const).
  double estimate(std::size_t i, std::size_t e, long M, const SobolShift& shift, long& rays) const {
    return estimate_with_spread(i, e, M, shift, rays).mean;
  }

  // The same estimate (bit-identical mean) with the spread of its samples: variance_of_mean = s^2 / M, s^2 the
  // unbiased sample variance of the scores f_s (0 for M = 1). For independent uniform samples it is an unbiased
  // estimate of the mean's variance; the Sobol points make the true variance smaller, by a factor that
  // formfactor/sampling_factor.h measures.
  struct Estimate {
    double mean = 0;
    double variance_of_mean = 0;
  };
  Estimate estimate_with_spread(std::size_t i, std::size_t e, long M, const SobolShift& shift, long& rays) const;

 private:
  const PatchSet& patches_;
  const Visibility& visibility_;
  double eps_ = 0;
};

}  // namespace radwalk
