#pragma once
// ProgressiveSeries: the iterates of a progressive solve as a ParaView time series,
//   DIR/step_0000.vtp, step_0001.vtp, ...  (one per kept iterate: the patch fields and the cell field B; field
//                                           data: iteration, residual, elapsed_seconds and the given metadata)
//   DIR/solve.pvd                          (time = iteration: sweep or shot count)
// so ParaView plays the convergence (open solve.pvd, colour by B, press play). residual is residual_of(B) (the
// relative residual of the system, solve/residual.h), computed only for the steps written; elapsed_seconds is the
// wall time since the series was created less the time spent writing it (the solver's own time to that iterate).
//
// Monte Carlo runs (random walks, path-traced patch averages) write a convergence series instead: add_estimate()
// writes one step per call, with B, B_se and the given step metadata, time = the walks or samples so far
// (doubling_counts below gives 1, 2, 4, ... batches).
//
// At most max_files steps are kept: every call is written while there is room; when the count reaches the limit,
// every other kept step is deleted and only every 2nd (then 4th, ...) later call is written. The last iterate is
// always included (finish).
//
// A series already in DIR stays whole until the new one is complete: every step is written to a pending temporary
// in DIR (core/atomic_write.h) and finish() publishes the steps and the .pvd together (commit_together: all were
// written completely before the first rename), then removes the earlier run's step_NNNN.vtp beyond the new count.
// A run that fails before (a full disk, the file-size limit, an error, a signal) removes its temporaries and
// leaves the old series readable; a DIR that the series created is removed again if it stays empty.
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/atomic_write.h"
#include "core/types.h"
#include "core/solution.h"
#include "core/timer.h"
#include "io/cell_field.h"
#include "io/run_summary.h"
#include "io/vtp_metadata.h"
#include "patch/patch_set.h"

namespace radwalk::app {

class ProgressiveSeries {
 public:
  // Creates DIR (InputError if it cannot) and checks that the collection can be written there. max_files >= 2.
  // The collection is DIR/pvd_name.
  ProgressiveSeries(std::string dir, const PatchSet& patches, std::function<double(const PatchRgb&)> residual_of,
                    VtpMetadata metadata = {}, std::size_t max_files = 200,
                    const std::string& pvd_name = "solve.pvd");
  // Without finish(): removes the steps written (the old series stays) and DIR if it was created and is empty.
  ~ProgressiveSeries();
  ProgressiveSeries(const ProgressiveSeries&) = delete;
  ProgressiveSeries& operator=(const ProgressiveSeries&) = delete;
  // One iterate (the solver's on_iterate callback).
  void add(long iteration, const PatchRgb& B);
  // One step of a convergence series: the estimate B with its standard error B_se after `count` walks or samples
  // (the time of the step; counts must increase), and the step's metadata (walks, B_se summary, seconds, ...).
  void add_estimate(long count, const PatchRgb& B, const PatchRgb& B_se, const VtpMetadata& step);
  // Writes the last iterate if it was skipped and the .pvd, then publishes the kept steps as step_0000.vtp ... in
  // order together with the .pvd, and removes the earlier run's steps beyond them. Returns the number of steps.
  std::size_t finish();
  long stride() const { return stride_; }
  const std::string& pvd_path() const { return pvd_; }

 private:
  void write(long iteration, const PatchRgb& B);
  void write_file(long time, std::vector<CellField> fields, VtpMetadata step);

  std::string dir_, pvd_;
  bool created_dir_ = false, finished_ = false;
  const PatchSet& patches_;
  std::vector<CellField> patch_fields_;  // patch_fields(patches_), the same in every step
  std::function<double(const PatchRgb&)> residual_of_;
  VtpMetadata metadata_;
  Timer clock_;
  double writing_seconds_ = 0;  // spent in write(), left out of elapsed_seconds
  std::size_t max_files_;
  long calls_ = 0, stride_ = 1;
  std::vector<std::pair<long, std::unique_ptr<PendingFile>>> kept_;  // (iteration, its step, not yet published)
  long last_iteration_ = -1;
  PatchRgb last_B_;
};

// The walk or sample counts of a convergence series that ends at `total`: ceil(total / 2^k) for k = K, ..., 1, 0
// with K = min(max_doublings, floor(log2 total)), without repeats and at least 2 (a standard error needs two
// samples) unless total is 1 (e.g. 1000 -> 2, 4, 8, 16, 32, 63, 125, 250, 500, 1000; 64 -> 2, 4, ..., 64). With counter-based streams (walk w, sample s), a run with n walks uses the first n walks of the
// full run, so each step is the full run's estimate after its first n walks.
std::vector<long> doubling_counts(long total, int max_doublings = 10);

// The convergence series of a Monte Carlo run of `total` walks or samples per patch (or particles): one step per
// doubling_counts(total), each the Solution of run(count) (the last one `full`, the run already made), written
// with add_estimate and solution_metadata (walks, B_se_relative_rms, solve_seconds, ...) plus the method and scene
// as the step's field data, into DIR/pvd_name. Costs about as much again as the full run. Records the series
// under "progressive" in the summary and says so on stderr.
void write_convergence_series(const std::string& dir, const std::string& pvd_name, const std::string& scene,
                              const PatchSet& patches, long total, const Solution& full,
                              const std::function<Solution(long count)>& run, RunSummary& summary);

}  // namespace radwalk::app
