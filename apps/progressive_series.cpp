#include "apps/progressive_series.h"

#include "core/distributed.h"

#include <cstdio>
#include <filesystem>
#include <regex>
#include <stdexcept>

#include "apps/pipeline.h"
#include "apps/run_metadata.h"
#include "core/error.h"
#include "io/cell_field.h"
#include "io/vtp_writer.h"

namespace fs = std::filesystem;

namespace radwalk::app {
namespace {

std::string step_name(std::size_t k) {
  char name[32];
  std::snprintf(name, sizeof name, "step_%04zu.vtp", k);
  return name;
}

}  // namespace

ProgressiveSeries::ProgressiveSeries(std::string dir, const PatchSet& patches,
                                     std::function<double(const PatchRgb&)> residual_of, VtpMetadata metadata,
                                     std::size_t max_files, const std::string& pvd_name)
    : dir_(std::move(dir)),
      patches_(patches),
      patch_fields_(patch_fields(patches)),
      residual_of_(std::move(residual_of)),
      metadata_(std::move(metadata)),
      max_files_(std::max<std::size_t>(max_files, 2)) {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec || !fs::is_directory(dir_)) throw InputError("--progressive " + dir_ + ": cannot create the directory");
  const std::regex stale("step_[0-9]{4,}\\.vtp");
  if (distributed::is_root())  // over MPI only rank 0 writes the series (core/distributed.h)
    for (const auto& entry : fs::directory_iterator(dir_))
      if (std::regex_match(entry.path().filename().string(), stale)) fs::remove(entry.path());
  pvd_ = (fs::path(dir_) / pvd_name).string();
}

void ProgressiveSeries::write(long iteration, const PatchRgb& B) {
  const double elapsed = clock_.seconds() - writing_seconds_;
  Timer writing;
  VtpMetadata step;
  step.set_integer("iteration", iteration);
  if (residual_of_) step.set_real("residual", residual_of_(B));
  step.set_real("elapsed_seconds", elapsed);
  writing_seconds_ += writing.seconds();
  write_file(iteration, {rgb_field("B", B)}, std::move(step));
}

void ProgressiveSeries::write_file(long time, std::vector<CellField> fields, VtpMetadata step) {
  Timer writing;
  std::vector<CellField> all = patch_fields_;
  all.insert(all.end(), fields.begin(), fields.end());
  step.merge(metadata_);
  const std::string file = (fs::path(dir_) / ("iterate_" + std::to_string(time) + ".vtp")).string();
  write_vtp(file, patches_, all, step);
  kept_.emplace_back(time, file);
  writing_seconds_ += writing.seconds();
}

void ProgressiveSeries::add_estimate(long count, const PatchRgb& B, const PatchRgb& B_se, const VtpMetadata& step) {
  if (!kept_.empty() && count <= kept_.back().first)
    throw std::logic_error("ProgressiveSeries::add_estimate: counts must increase");
  write_file(count, {rgb_field("B", B), rgb_field("B_se", B_se)}, step);
  last_iteration_ = count;
}

void ProgressiveSeries::add(long iteration, const PatchRgb& B) {
  ++calls_;
  last_iteration_ = iteration;
  last_B_ = B;
  if (calls_ % stride_ != 0) return;
  write(iteration, B);
  if (kept_.size() + 1 >= max_files_) {
    // Thin: keep the steps at multiples of 2 x stride (odd positions, since position k holds call (k+1) x stride).
    std::vector<std::pair<long, std::string>> thinned;
    for (std::size_t k = 0; k < kept_.size(); ++k) {
      if (k % 2 == 1) thinned.push_back(kept_[k]);
      else if (distributed::is_root()) fs::remove(kept_[k].second);
    }
    kept_ = std::move(thinned);
    stride_ *= 2;
  }
}

std::size_t ProgressiveSeries::finish() {
  if (last_iteration_ >= 0 && (kept_.empty() || kept_.back().first != last_iteration_) && last_B_.rows() > 0)
    write(last_iteration_, last_B_);
  std::vector<std::pair<double, std::string>> steps;
  for (std::size_t k = 0; k < kept_.size(); ++k) {
    if (distributed::is_root())  // the other ranks' files were not written (core/atomic_write.h)
      fs::rename(kept_[k].second, fs::path(dir_) / step_name(k));
    steps.emplace_back(double(kept_[k].first), step_name(k));
  }
  write_pvd(pvd_, steps);
  return steps.size();
}

std::vector<long> doubling_counts(long total, int max_doublings) {
  std::vector<long> counts;
  if (total <= 0) return counts;
  int K = 0;
  while (K < max_doublings && (2L << K) <= total) ++K;
  for (int k = K; k >= 0; --k) {
    const long n = (total + (1L << k) - 1) >> k;
    if ((n >= 2 || n == total) && (counts.empty() || n > counts.back())) counts.push_back(n);
  }
  return counts;
}

void write_convergence_series(const std::string& dir, const std::string& pvd_name, const std::string& scene,
                              const PatchSet& patches, long total, const Solution& full,
                              const std::function<Solution(long count)>& run, RunSummary& summary) {
  VtpMetadata metadata;
  metadata.set_text("run_id", run_id_of(summary));
  metadata.set_text("method", full.method);
  metadata.set_text("scene", scene);
  ProgressiveSeries series(dir, patches, nullptr, metadata, 200, pvd_name);
  for (const long count : doubling_counts(total)) {
    const Solution s = count == total ? full : run(count);
    VtpMetadata step = solution_metadata(s, patches);
    step.set_integer("count", count);
    series.add_estimate(count, s.B, s.B_se, step);
  }
  const std::size_t steps = series.finish();
  summary.json()["progressive"] = {{"pvd", series.pvd_path()}, {"steps", steps}};
  note("wrote " + series.pvd_path() + " (" + std::to_string(steps) +
       " steps: the estimate after 1, 2, 4, ... batches)");
}

}  // namespace radwalk::app
