#pragma once
// Form factors with the columns of the emitters exact where unoccluded (the recommended form-factor route, docs/measurements.md "Which method when"):
// the cosine rays of estimate_form_factors (form_factors.h) estimate every entry, then each entry F_ie of an
// emitter column e (a patch with E_e > 0 in some channel) is replaced by the VisibleFormFactor estimate
// (visible_form_factor.h: Lambert's point-to-polygon form factor at Sobol points x of patch i, corrected for
// occlusion by one shadow ray per point). The cosine rays that landed on e are dropped from the row (their
// count estimated the same entry, with the binomial noise of a small target: a 1 % entry from 1000 rays has a
// relative standard error of 31 %).
//
// Per row: M = shadow_samples_per_patch samples in all, split evenly over the emitter columns with F(x -> e) > 0
// somewhere (at least 1 each); sample s of column e uses the shift of stream (seed, emitter_form_factor, i, e).
// Each replaced entry is unbiased; it is stored as max(0, estimate) so that F stays non-negative (the solvers
// refuse F_ij < 0), which biases only entries in (near) full shadow, whose true value is within the estimate's
// noise of 0, by at most that noise / sqrt(2 pi). Row sums are the sum of the stored entries: the dropped cosine
// hits are replaced by an unbiased estimate of the same mass, so a closed scene's rows still sum to 1 in
// expectation (escaped and back_hits still count the cosine rays). A row's other entries are those of the cosine
// rays, unchanged. Emitter patches' own rows are treated like every other row. Deterministic: the result does not
// depend on the thread count.
#include <cstdint>
#include <string>
#include <vector>

#include "formfactor/form_factors.h"
#include "formfactor/visible_form_factor.h"

namespace radwalk {

struct EmitterFormFactors {
  FormFactors form_factors;   // F with the emitter columns replaced; rays/escaped/back_hits of the cosine rays
  std::size_t emitter_columns = 0;
  long shadow_rays = 0;       // shadow rays traced for the replaced columns (all rows)
};

// The cosine rays per patch come from `options`; shadow_samples_per_patch >= 1 (InputError otherwise). The result's
// form_factors also record the replaced columns and each replaced entry's variance (form_factors.h).
EmitterFormFactors estimate_emitter_form_factors(const PatchSet& patches, const Visibility& visibility,
                                                 const FormFactorOptions& options, long shadow_samples_per_patch);

// The same replacement applied to F already traced by cosine rays (estimate_form_factors, or over MPI
// estimate_form_factor_rows: then only the rows this process holds are replaced, each the same bits as one
// process gives it). form_factors.options must be those it was traced with (their seed picks the streams).
EmitterFormFactors replace_emitter_columns(FormFactors form_factors, const PatchSet& patches,
                                           const Visibility& visibility, long shadow_samples_per_patch);

// The shadow samples per patch M for a request: `requested` >= 0 is taken as given (0: no emitter columns);
// kAutoEmitterSamples chooses M = round(mean cosine rays per patch / 3), at least 1 (a quarter of all the rays on
// the emitter columns, the setting measured best on the Cornell box, docs/measurements.md), for small lights: when
// the emitters cover at most kMaxEmitterAreaFraction of the area, the scene has between 1 and M emitter patches and
// N x emitters stays within kMaxEmitterEntries; otherwise 0 (large emitters get many cosine hits, and where most
// patches emit, as in a thermal scene or a furnace, every row would need at least one sample per emitter it sees;
// there the cosine rays' rows also sum to exactly 1 in a closed scene). `reason` says which, for the summary.
inline constexpr long kAutoEmitterSamples = -1;
inline constexpr double kMaxEmitterEntries = double(1 << 24);
inline constexpr double kMaxEmitterAreaFraction = 0.1;
struct EmitterSampleChoice {
  long samples = 0;
  std::string reason;
};
EmitterSampleChoice choose_emitter_samples(const PatchSet& patches, const FormFactorOptions& options,
                                           long requested);

// F by cosine rays with `options` (every row), then the emitter columns of choose_emitter_samples(emitter_request)
// when it chooses any: the route of the CLI's form-factor stage without its reports.
FormFactors estimate_form_factors_with_emitters(const PatchSet& patches, const Visibility& visibility,
                                                const FormFactorOptions& options, long emitter_request);

// The emitters: the patches with E > 0 in some channel, increasing.
std::vector<std::size_t> emitter_patches(const PatchSet& patches);

// Row i's emitter entries as estimate_emitter_form_factors computes them (the same streams of options.seed):
// for each emitter e (of `emitters`) that i may see, the raw estimate of F_ie (before the clamp at 0) and its
// variance (VisibleFormFactor::estimate_with_spread); the shadow rays are added to `rays`.
struct EmitterEntry {
  std::size_t column = 0;
  double value = 0;
  double variance = 0;
};
std::vector<EmitterEntry> estimate_emitter_row(const PatchSet& patches, const VisibleFormFactor& visible,
                                               const FormFactorOptions& options, long shadow_samples_per_patch,
                                               const std::vector<std::size_t>& emitters, std::size_t i, long& rays);

}  // namespace radwalk
