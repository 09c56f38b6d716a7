#pragma once
// ProgressiveSeries: the iterates of a progressive solve as a ParaView time series,
//   DIR/step_0000.vtp, step_0001.vtp, ...  (one per kept iterate: the patch fields and the cell field B; field
//                                           data: iteration, residual, elapsed_seconds and the given metadata)
//   DIR/solve.pvd                          (time = iteration: sweep or shot count)
// so ParaView plays the convergence (open solve.pvd, colour by B, press play). residual is residual_of(B) (the
// relative residual of the system, solve/residual.h), computed only for the steps written; elapsed_seconds is the
// wall time since the series was created less the time spent writing it (the solver's own time to that iterate).
//
// At most max_files steps are kept: every call is written while there is room; when the count reaches the limit,
// every other kept step is deleted and only every 2nd (then 4th, ...) later call is written. The last iterate is
// always included (finish). Stale step_NNNN.vtp files in DIR from an earlier run are removed at the start.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/types.h"
#include "core/timer.h"
#include "io/cell_field.h"
#include "io/vtp_metadata.h"
#include "patch/patch_set.h"

namespace radwalk::app {

class ProgressiveSeries {
 public:
  // Creates DIR (InputError if it cannot). max_files >= 2.
  ProgressiveSeries(std::string dir, const PatchSet& patches, std::function<double(const PatchRgb&)> residual_of,
                    VtpMetadata metadata = {}, std::size_t max_files = 200);
  // One iterate (the solver's on_iterate callback).
  void add(long iteration, const PatchRgb& B);
  // Writes the last iterate if it was skipped, renames the kept steps to step_0000.vtp ... in order and writes
  // solve.pvd. Returns the number of steps.
  std::size_t finish();
  long stride() const { return stride_; }
  const std::string& pvd_path() const { return pvd_; }

 private:
  void write(long iteration, const PatchRgb& B);

  std::string dir_, pvd_;
  const PatchSet& patches_;
  std::vector<CellField> patch_fields_;  // patch_fields(patches_), the same in every step
  std::function<double(const PatchRgb&)> residual_of_;
  VtpMetadata metadata_;
  Timer clock_;
  double writing_seconds_ = 0;  // spent in write(), left out of elapsed_seconds
  std::size_t max_files_;
  long calls_ = 0, stride_ = 1;
  std::vector<std::pair<long, std::string>> kept_;  // (iteration, file)
  long last_iteration_ = -1;
  PatchRgb last_B_;
};

}  // namespace radwalk::app
