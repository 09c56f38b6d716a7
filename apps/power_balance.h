#pragma once
// Where the emitted power goes, in every solve and path trace: the JSON's `power_balance` (docs/json-schema.md).
//
// A patch i of radiosity B_i sends power A_i B_i (channel mean) into the scene; of the cosine-distributed rays
// leaving it (the form-factor rays, or rays traced for this balance alone), a fraction q_i escapes the scene and
// a fraction b_i hits the back of a one-sided face, whose back absorbs it (docs/two-sided.md). So of the emitted
// power P = sum_i A_i E_i:
//   escaped             = sum_i A_i B_i q_i / P
//   lost_to_back_faces  = sum_i A_i B_i b_i / P
//   absorbed            = 1 - escaped - lost_to_back_faces   (by the fronts of faces, in steady state)
// with standard errors from the binomial counts, sum_i (A_i B_i)^2 p_i (1 - p_i) / n_i, and where B has one
// (Monte Carlo solvers), sum_i (A_i p_i se(B_i))^2, added in quadrature. Above 1 % lost to back faces is a warning
// (faces oriented the wrong way, an inside-out room, open or thin parts that should be two-sided).
#include <cstdint>
#include <vector>

#include "core/types.h"
#include "io/run_summary.h"
#include "patch/patch_set.h"

namespace radwalk::app {

struct RayFates {
  std::vector<std::uint32_t> rays, escaped, back_hits;  // per patch; empty when unknown (F read from a file)
};

// Counts for the balance alone: `rays` cosine rays per patch (formfactor/form_factors.h, the form-factor rays of
// seed `seed`, counted row by row: F is never assembled, memory O(N)). Empty when the scene has more than
// max_patches patches (not worth the time).
RayFates trace_ray_fates(const PatchSet& patches, std::uint64_t seed, long rays = 128, std::size_t max_patches = 2000000);

// Writes summary["power_balance"] and warns above 1 % lost to back faces. B_se may be empty.
void report_power_balance(const PatchSet& patches, const PatchRgb& B, const PatchRgb& B_se, const RayFates& fates,
                          RunSummary& summary);

}  // namespace radwalk::app
