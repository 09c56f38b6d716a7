#pragma once
// RayKernel: the transition kernel that traces each step instead of storing F (transition_kernel.h).
//
// sample(k): a uniform point x on patch k (sample_patch_point), a cosine-weighted direction about n_k, a ray
// from spawn_ray traced through the Visibility. A front-face hit on patch j returns j, which happens with
// probability F_kj (the exact form factor of the geometry, up to the ray offset of ray_offset.h); a miss returns
// kEscaped and a back-face hit kBackHit, both ending the walk (counted). So n_k = 1, and the walk needs O(N)
// memory. Four uniforms per ray: (u1, u2) for the point, (u3, u4) for the direction.
// Scored stops for gathering absorption are the roulette stops only (a_k = 1 - p_k): the escape probability
// 1 - s_k is unknown without F, so an escape scores 0 (still unbiased).
// HE(k) traces one extra, independent ray: rho_k E_j if it hits the front of j, else 0; E[.] = (H E)_k.
#include "core/sampling.h"
#include "patch/patch_set.h"
#include "solve/problem.h"
#include "visibility/visibility.h"
#include "walk/transition_kernel.h"

namespace radwalk {

class RayKernel {
 public:
  static constexpr bool kEscapeScores = false;
  // rho and E come from `problem` (F is not used and may be empty); geometry from `patches`, which, like
  // `visibility`, must outlive the kernel. Throws InputError on sizes that disagree.
  RayKernel(const RadiosityProblem& problem, const PatchSet& patches, const Visibility& visibility,
            std::vector<double> p);

  std::size_t size() const { return patches_.size(); }
  double survival(std::size_t k) const { return tables_.p[k]; }
  double row_scale(std::size_t /*k*/) const { return 1.0; }
  const WalkTables& tables() const { return tables_; }

  PatchIndex sample(std::size_t k, Rng& rng, WalkCounters& counters) const;
  Rgb HE(std::size_t k, Rng& rng, WalkCounters& counters) const {
    const PatchIndex j = sample(k, rng, counters);
    return j >= 0 ? Rgb(tables_.rho[k] * tables_.E[static_cast<std::size_t>(j)]) : Rgb::Zero();
  }

 private:
  const PatchSet& patches_;
  const Visibility& visibility_;
  double eps_;
  std::vector<Frame> frames_;
  WalkTables tables_;
};

}  // namespace radwalk
