// radwalk formfactors SCENE [--rays N | --rays-per-area D] -o F.mtx|F.npz [--csv] [--vtp] [--json]
#include <algorithm>
#include <cstdio>

#include "apps/options.h"
#include "apps/pipeline.h"
#include "apps/run_metadata.h"
#include "core/timer.h"
#include "formfactor/form_factor_file.h"

namespace radwalk::app {

int run_formfactors(const FormFactorsCommand& command) {
  RunSummary summary("formfactors", command.scene.argv);
  const PatchSet patches = load_patches(command.scene, summary);
  const FormFactors ff = obtain_form_factors(command.scene, command.ff, patches, summary);
  if (!command.mtx.empty()) {
    Timer timer;
    write_form_factors(command.mtx, ff.F, run_id_of(summary));  // .npz or .mtx
    summary.add_timing("write_matrix", timer.seconds());
    note("wrote " + command.mtx);
  }
  const std::vector<CellField> diagnostics = form_factor_fields(ff, patches);

  // Summary on stdout: closure and reciprocity over all patches.
  const auto& row_sum = diagnostics[0].values;
  const auto& recip = diagnostics[1].values;
  const double min_row = *std::min_element(row_sum.begin(), row_sum.end());
  const double max_row = *std::max_element(row_sum.begin(), row_sum.end());
  const double max_recip = *std::max_element(recip.begin(), recip.end());
  std::printf("%zu patches, %ld non-zeros (%.1f per row); row sums in [%.6f, %.6f]; max reciprocity error %.3g\n",
              patches.size(), static_cast<long>(ff.F.nonZeros()), double(ff.F.nonZeros()) / patches.size(), min_row,
              max_row, max_recip);
  summary.json()["row_sum_min"] = min_row;
  summary.json()["row_sum_max"] = max_row;
  SceneOptions outputs = command.scene;
  outputs.vtp = command.diagnostics_vtp;
  write_outputs(outputs, patches, diagnostics, summary);
  return 0;
}

}  // namespace radwalk::app
