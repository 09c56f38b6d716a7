#include "apps/progressive_series.h"

#include <cstdio>
#include <filesystem>
#include <regex>

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
                                     std::size_t max_files)
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
  for (const auto& entry : fs::directory_iterator(dir_))
    if (std::regex_match(entry.path().filename().string(), stale)) fs::remove(entry.path());
  pvd_ = (fs::path(dir_) / "solve.pvd").string();
}

void ProgressiveSeries::write(long iteration, const PatchRgb& B) {
  const double elapsed = clock_.seconds() - writing_seconds_;
  Timer writing;
  std::vector<CellField> fields = patch_fields_;
  fields.push_back(rgb_field("B", B));
  VtpMetadata step;
  step.set_integer("iteration", iteration);
  if (residual_of_) step.set_real("residual", residual_of_(B));
  step.set_real("elapsed_seconds", elapsed);
  step.merge(metadata_);
  const std::string file = (fs::path(dir_) / ("iterate_" + std::to_string(iteration) + ".vtp")).string();
  write_vtp(file, patches_, fields, step);
  kept_.emplace_back(iteration, file);
  writing_seconds_ += writing.seconds();
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
      else fs::remove(kept_[k].second);
    }
    kept_ = std::move(thinned);
    stride_ *= 2;
  }
}

std::size_t ProgressiveSeries::finish() {
  if (last_iteration_ >= 0 && (kept_.empty() || kept_.back().first != last_iteration_))
    write(last_iteration_, last_B_);
  std::vector<std::pair<double, std::string>> steps;
  for (std::size_t k = 0; k < kept_.size(); ++k) {
    fs::rename(kept_[k].second, fs::path(dir_) / step_name(k));
    steps.emplace_back(double(kept_[k].first), step_name(k));
  }
  write_pvd(pvd_, steps);
  return steps.size();
}

}  // namespace radwalk::app
