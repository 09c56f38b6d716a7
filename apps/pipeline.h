#pragma once
// The stages every command shares: load + validate + patch a scene, obtain form factors, write outputs.
// Each stage is timed into the RunSummary; warnings go to stderr and to the summary.
#include <string>
#include <vector>

#include "apps/options.h"
#include "formfactor/form_factors.h"
#include "io/cell_field.h"
#include "io/vtp_metadata.h"
#include "io/run_summary.h"
#include "mesh/mesh.h"
#include "patch/patch_set.h"

namespace radwalk::app {

// Reads and validates the scene (throws InputError on refusal), prints the repairs as warnings; the summary also
// gets the warnings printed while reading the command line (options.warnings). Output file names were checked
// then too (apps/output_files.h).
Mesh load_validated_mesh(const SceneOptions& options, RunSummary& summary);

// load_validated_mesh, then make_patches with options.max_edge and max_area; notes the patch count and area
// distribution (min, median, max; JSON `patch_area`).
PatchSet load_patches(const SceneOptions& options, RunSummary& summary);

// Form factors for the patches: read from --form-factors (ray counts left empty) or estimated with Embree
// (timed as "form_factors"); --reciprocity is applied either way and its change reported.
FormFactors obtain_form_factors(const SceneOptions& scene, const FormFactorCliOptions& options,
                                const PatchSet& patches, RunSummary& summary);

// Per-patch form-factor diagnostics as cell fields: row_sum, escaped, back_hits, reciprocity_error,
// row_std_error (the counts only when F was estimated here).
std::vector<CellField> form_factor_fields(const FormFactors& ff, const PatchSet& patches);

// Writes -o FILE.vtp, --csv and --json where asked, timing the stage "write". `fields` are the command's own
// per-patch results; both files also carry the patch description (patch_fields: patch, face, area, normal, rho,
// E), which the CSV writes as its fixed leading columns. The .vtp's field data are run_metadata (run_metadata.h)
// and then `metadata` (the command's own: method, walks, spp, ...); --paraview-state FILE.py writes a ParaView
// state for the .vtp from the scene's camera (scene_camera.h).
void write_outputs(const SceneOptions& options, const PatchSet& patches, const std::vector<CellField>& fields,
                   RunSummary& summary, const VtpMetadata& metadata = {});

// Prints "radwalk: warning: ..." and records it in the summary.
void warn(RunSummary& summary, const std::string& message);

// Prints an informational line on stderr ("radwalk: ..."), unless set_quiet(true) (--quiet).
void note(const std::string& message);
void set_quiet(bool quiet);

}  // namespace radwalk::app
