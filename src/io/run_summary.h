#pragma once
// RunSummary: the JSON record of one run (command, arguments, versions, counts, stage timings, memory, warnings,
// solver results). Stages are timed in the order they ran; write() adds the peak memory and writes atomically.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace radwalk {

class RunSummary {
 public:
  RunSummary(std::string command, const std::vector<std::string>& arguments);

  // json()["key"] = value, for counts, options and results.
  nlohmann::json& json() { return json_; }
  // Records the wall time of a named stage ("load", "patch", "form factors", "solve", "write").
  void add_timing(const std::string& stage, double seconds);
  void add_warning(const std::string& warning);

  // Writes the summary to path (atomically), adding peak memory and the warnings.
  void write(const std::string& path);

 private:
  nlohmann::json json_;
  std::vector<std::string> warnings_;
};

// Versions of radwalk and of the libraries it was built with.
nlohmann::json library_versions();

}  // namespace radwalk
