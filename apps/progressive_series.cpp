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

// The target every step's temporary is created for until finish() knows its place in the series (so that the
// temporaries a killed run left are removed by the next series written in DIR, core/atomic_write.h).
constexpr const char* kStagedStep = "step_NNNN.vtp";

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
  if (dir_.empty()) throw InputError("--progressive needs a directory name");
  std::error_code ec;
  created_dir_ = !fs::is_directory(dir_, ec);
  fs::create_directories(dir_, ec);
  if (ec || !fs::is_directory(dir_, ec)) throw InputError("--progressive " + dir_ + ": cannot create the directory");
  pvd_ = (fs::path(dir_) / pvd_name).string();
  require_output_directory(pvd_);  // the collection can be written (not a directory, say), before any step
}

ProgressiveSeries::~ProgressiveSeries() {
  kept_.clear();  // removes the temporaries of the steps not published
  std::error_code ec;
  if (!finished_ && created_dir_ && distributed::is_root()) fs::remove(dir_, ec);  // only if empty
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
  const std::string staged = (fs::path(dir_) / kStagedStep).string();
  std::unique_ptr<PendingFile> file;
  if (distributed::is_root()) {
    file = std::make_unique<PendingFile>(staged);
    file->write_via_path([&](const std::string& temporary) { write_vtp(temporary, patches_, all, step); });
  } else {
    write_vtp(staged, patches_, all, step);  // over MPI only rank 0 writes: the same work, discarded (atomic_write.h)
  }
  kept_.emplace_back(time, std::move(file));
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
    // Thin: keep the steps at multiples of 2 x stride (odd positions, since position k holds call (k+1) x stride);
    // a step dropped removes its temporary.
    decltype(kept_) thinned;
    for (std::size_t k = 0; k < kept_.size(); ++k)
      if (k % 2 == 1) thinned.push_back(std::move(kept_[k]));
    kept_ = std::move(thinned);
    stride_ *= 2;
  }
}

std::size_t ProgressiveSeries::finish() {
  if (last_iteration_ >= 0 && (kept_.empty() || kept_.back().first != last_iteration_) && last_B_.rows() > 0)
    write(last_iteration_, last_B_);
  std::vector<std::pair<double, std::string>> steps;
  if (!distributed::is_root()) {  // nothing was written on this rank (write_file)
    for (std::size_t k = 0; k < kept_.size(); ++k) steps.emplace_back(double(kept_[k].first), step_name(k));
    write_pvd(pvd_, steps);
    finished_ = true;
    kept_.clear();
    return steps.size();
  }
  // Each kept step's temporary becomes the temporary of its name in the series (a rename in DIR: no space needed).
  std::vector<std::unique_ptr<PendingFile>> files;
  for (std::size_t k = 0; k < kept_.size(); ++k) {
    auto file = std::make_unique<PendingFile>((fs::path(dir_) / step_name(k)).string());
    const std::string staged = kept_[k].second->temporary();
    file->write_via_path([&](const std::string& temporary) {
      std::error_code ec;
      fs::rename(staged, temporary, ec);
      if (ec) throw InputError(file->path() + ": cannot write output: rename failed (" + ec.message() + ")");
    });
    kept_[k].second.reset();  // its temporary is gone; frees its slot in the signal-cleanup table
    files.push_back(std::move(file));
    steps.emplace_back(double(kept_[k].first), step_name(k));
  }
  PendingFile pvd(pvd_);
  pvd.write_via_path([&](const std::string& temporary) { write_pvd(temporary, steps); });
  // Published together: every step and the collection were written completely before the first rename.
  std::vector<PendingFile*> together;
  for (const auto& f : files) together.push_back(f.get());
  together.push_back(&pvd);
  commit_together(together);
  finished_ = true;
  kept_.clear();
  // The earlier run's steps beyond this series (a longer series before) are no longer in the collection.
  const std::regex numbered("step_([0-9]{4,})\\.vtp");
  std::error_code ec;
  std::vector<fs::path> stale;
  for (fs::directory_iterator it(dir_, ec), end; !ec && it != end; it.increment(ec)) {
    std::smatch m;
    const std::string name = it->path().filename().string();
    if (std::regex_match(name, m, numbered) && (m[1].length() > 9 || std::stoul(m[1].str()) >= steps.size()))
      stale.push_back(it->path());
  }
  for (const fs::path& p : stale) fs::remove(p, ec);
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
