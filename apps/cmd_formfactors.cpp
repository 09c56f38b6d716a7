// radwalk formfactors SCENE [--rays N | --rays-per-area D] -o F.mtx|F.npz [--csv] [--vtp] [--json]
#include <algorithm>
#include <cstdio>
#include <cstdint>

#include "apps/options.h"
#include "apps/pipeline.h"
#include "apps/run_metadata.h"
#include "core/timer.h"
#include "formfactor/emitter_form_factors.h"
#include "formfactor/form_factor_file.h"

namespace radwalk::app {

int run_formfactors(const FormFactorsCommand& command) {
  RunSummary summary("formfactors", command.scene.argv);
  const PatchSet patches = load_patches(command.scene, summary);
  // Over MPI each rank traces and keeps its rows; rank 0 gathers the whole F (the others' rows in rank order) to
  // write the one file, the same bytes as one process's, and to compute the diagnostics, then drops it.
  // F as geometry: the emitter columns serve the lighting of one solve (their entries are unbiased but a row may
  // sum above 1), so `auto` means none here; --emitter-columns M still asks for them.
  FormFactorCliOptions options = command.ff;
  if (options.emitter_samples == kAutoEmitterSamples) options.emitter_samples = 0;
  const FormFactors ff = obtain_form_factors(command.scene, options, patches, summary, RowsHeld::own_rows);
  const std::uint64_t nonzeros = total_nonzeros(ff.F, ff.row_blocks);
  std::vector<CellField> diagnostics;
  {
    SparseF gathered;
    const SparseF& whole = gather_rows_to_root(ff.F, ff.row_blocks, gathered);
    if (!command.mtx.empty()) {
      Timer timer;
      write_form_factors(command.mtx, whole, run_id_of(summary));  // .npz or .mtx (rank 0 writes)
      summary.add_timing("write_matrix", timer.seconds());
      note("wrote " + command.mtx);
    }
    diagnostics = form_factor_fields(ff, patches, &whole);
  }

  // Summary on stdout: closure and reciprocity over all patches.
  const auto& row_sum = diagnostics[0].values;
  const auto& recip = diagnostics[1].values;
  const double min_row = *std::min_element(row_sum.begin(), row_sum.end());
  const double max_row = *std::max_element(row_sum.begin(), row_sum.end());
  const double max_recip = *std::max_element(recip.begin(), recip.end());
  std::fprintf(report_stream(), "%zu patches, %ld non-zeros (%.1f per row); row sums in [%.6f, %.6f]; max reciprocity error %.3g\n",
              patches.size(), static_cast<long>(nonzeros), double(nonzeros) / patches.size(), min_row,
              max_row, max_recip);
  summary.json()["row_sum_min"] = min_row;
  summary.json()["row_sum_max"] = max_row;
  SceneOptions outputs = command.scene;
  outputs.vtp = command.diagnostics_vtp;
  write_outputs(outputs, patches, diagnostics, summary);
  return 0;
}

}  // namespace radwalk::app
