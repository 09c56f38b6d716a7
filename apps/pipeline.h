#pragma once
// The stages every command shares: load + validate + patch a scene, obtain form factors, write outputs.
// Each stage is timed into the RunSummary; warnings go to stderr and to the summary.
#include <cstdio>
#include <string>
#include <vector>

#include "apps/options.h"
#include "formfactor/form_factors.h"
#include "io/cell_field.h"
#include "io/vtp_metadata.h"
#include "io/run_summary.h"
#include "mesh/length_unit.h"
#include "mesh/mesh.h"
#include "patch/contact_patches.h"
#include "patch/patch_set.h"

namespace radwalk::app {

// Reads the scene, applies the material overrides (--set, --rho-scale: mesh/material_override.h) and validates it,
// prints the repairs, warnings and notes grouped by kind (mesh/validate.h); the summary gets every finding
// ("findings"), the overrides, and the warnings printed while reading the command line (options.warnings). On
// refusal every finding is printed (errors grouped by kind after the warnings), --json is written with them
// ("refused": true) unless it names a file the readers read (then it is refused, never written), and an InputError
// with one summary line is thrown. Output file names were checked while reading the command line
// (apps/output_files.h), the material libraries here. Collective over MPI: the ranks then compare the bytes they
// read and whether they refused them (apps/rank_agreement.h, agree_on_inputs), and on a difference every rank
// throws one InputError naming it.
Mesh load_validated_mesh(const SceneOptions& options, RunSummary& summary);

// The length unit of the scene after --scale, as --unit names the file's (mesh/length_unit.h); the summaries'
// "units" (length, radiosity).
LengthUnit length_unit(const SceneOptions& options);

// load_validated_mesh, then patch_scene (patch/patch_scene.h, as radwalk.load: the contacts, cut with
// --contact-cut when faces are split; make_patches with options.max_edge and max_area; add_back_sides, the faces
// of two-sided materials, or all with --two-sided, a back patch each after all front patches). Notes the contacts
// (JSON `contacts`, `contact_cut`, `contact_faces_cut`), the patch count and area distribution (min, median, max;
// JSON `patch_area`).
PatchSet load_patches(const SceneOptions& options, RunSummary& summary);
// The same, keeping the validated mesh (its groups and source lines) in `mesh`.
// regions, if given, gets the contact regions (patch/contact_patches.h, on the mesh before any cut).
PatchSet load_patches(const SceneOptions& options, RunSummary& summary, Mesh& mesh,
                      std::vector<ContactRegion>* regions = nullptr);

// Which rows of F each rank holds over MPI: every row (what every consumer of F can use), or only its own block
// (formfactor/form_factor_rows.h: for Jacobi, Gauss-Seidel and writing F; ff.row_blocks says which). The same
// with one process.
enum class RowsHeld { every_row, own_rows };

// Form factors for the patches: read from --form-factors (ray counts left empty) or estimated with Embree
// (timed as "form_factors"); --reciprocity is applied either way and its change reported (over MPI on the whole F,
// gathered for it). Over MPI the JSON's mpi.form_factor_nonzeros_by_rank records what each rank holds.
FormFactors obtain_form_factors(const SceneOptions& scene, const FormFactorCliOptions& options,
                                const PatchSet& patches, RunSummary& summary, RowsHeld held = RowsHeld::every_row);

// The same estimate (rays with the emitter columns, or the analytic route, then --reciprocity) without notes,
// summary or MPI distribution, for the patches of a re-patched scene (--refine, --target-error).
FormFactors trace_form_factors(const SceneOptions& scene, const FormFactorCliOptions& options, const PatchSet& patches);

// Per-patch form-factor diagnostics as cell fields: row_sum, escaped, back_hits, reciprocity_error,
// row_std_error (the counts only when F was estimated here). Collective over MPI when ff is row-distributed:
// rank 0 computes them on the whole F (`gathered`, from gather_rows_to_root, when the caller has it; otherwise
// gathered here for the time of the computation) and broadcasts them.
std::vector<CellField> form_factor_fields(const FormFactors& ff, const PatchSet& patches,
                                          const SparseF* gathered = nullptr);

// Writes -o FILE.vtp, --csv and --json where asked, timing the stage "write". `fields` are the command's own
// per-patch results; both files also carry the patch description (patch_fields: patch, face, area, normal, rho,
// E), which the CSV writes as its fixed leading columns. The .vtp's field data are run_metadata (run_metadata.h)
// and then `metadata` (the command's own: method, walks, spp, ...); --paraview-state FILE.py writes a ParaView
// state for the .vtp (io/paraview_state.h): coloured by B (radiosity_colouring of the field B, if given), from the
// camera of the one camera rule (scene_camera.h, as pathtrace fits it).
void write_outputs(const SceneOptions& options, const PatchSet& patches, const std::vector<CellField>& fields,
                   RunSummary& summary, const VtpMetadata& metadata = {});

// Prints "radwalk: warning: ..." and records it in the summary.
void warn(RunSummary& summary, const std::string& message);
// The same for a warning about the scene (a repair or warning that validation found), which with set_quiet(true)
// is not printed but counted (the scene's findings can be thousands; --json lists them all).
void warn_scene(RunSummary& summary, const std::string& message);
// The scene warnings warn_scene did not print because of --quiet.
long silenced_warnings();

// Prints an informational line on stderr ("radwalk: ..."), unless set_quiet(true) (--quiet).
void note(const std::string& message);
void set_quiet(bool quiet);

// Where a command prints its results for a reader (summary lines, tables): stdout, or stderr once
// report_to_stderr_if_stdout_written saw --csv - or --json - (core/standard_output.h), so that stdout carries exactly
// that output. Errors, warnings, notes and progress always go to stderr.
std::FILE* report_stream();
void report_to_stderr_if_stdout_written(const SceneOptions& options);

}  // namespace radwalk::app
