#pragma once
// --enforce-closure: the least-squares closure and reciprocity adjustment of F (formfactor/closure.h,
// docs/theory/closure.md) for the commands that obtain form factors, with its refusal on open scenes and its report.
#include "apps/run_metadata.h"
#include "formfactor/form_factors.h"
#include "patch/patch_set.h"

namespace radwalk::app {

// A scene is taken as closed when, with traced F, at most this fraction of all rays escaped or hit a back (the
// rounding leaks of watertight meshes), and, with analytic or read F, no row sums below 1 - this tolerance.
inline constexpr double kClosureLeakTolerance = 1e-3;

// Adjusts ff.F (every row held) so that rows sum to 1 and A_i F_ij = A_j F_ji, or throws InputError naming the
// patch that leaks most when the scene is open (the adjustment would send the escaping radiation back into the
// scene). Writes the change into the summary (JSON `closure`), a note line with max and RMS change, and per row
// into ff.closure_max_change and ff.closure_rms_change; the leaked rays are counted into F, so ff.escaped and
// ff.back_hits are set to 0 (their totals before are in the JSON, closure.rays_leaked_total). `source` names where F came from.
void apply_closure(FormFactors& ff, const PatchSet& patches, RunSummary& summary, const std::string& source);

}  // namespace radwalk::app
