#include "io/run_summary.h"

#include <embree3/rtcore_config.h>
#include <vtkVersionMacros.h>

#include <Eigen/Core>
#include <ostream>

#include "core/atomic_write.h"
#include "core/timer.h"

#ifndef RADWALK_VERSION
#define RADWALK_VERSION "unknown"
#endif

namespace radwalk {

RunSummary::RunSummary(std::string command, const std::vector<std::string>& arguments) {
  json_["radwalk"] = RADWALK_VERSION;
  json_["command"] = std::move(command);
  json_["arguments"] = arguments;
  json_["versions"] = library_versions();
  json_["timings_s"] = nlohmann::json::object();
}

void RunSummary::add_timing(const std::string& stage, double seconds) { json_["timings_s"][stage] = seconds; }

void RunSummary::add_warning(const std::string& warning) { warnings_.push_back(warning); }

void RunSummary::write(const std::string& path) {
  json_["peak_memory_bytes"] = peak_memory_bytes();
  json_["warnings"] = warnings_;
  const std::string text = json_.dump(2);
  write_atomically(path, [&](std::ostream& out) { out << text << '\n'; });
}

nlohmann::json library_versions() {
  nlohmann::json v;
  v["eigen"] = std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) + "." +
               std::to_string(EIGEN_MINOR_VERSION);
  v["embree"] = std::to_string(RTC_VERSION_MAJOR) + "." + std::to_string(RTC_VERSION_MINOR) + "." +
                std::to_string(RTC_VERSION_PATCH);
  v["vtk"] = VTK_VERSION;
  return v;
}

}  // namespace radwalk
