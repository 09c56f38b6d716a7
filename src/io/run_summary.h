#pragma once
// RunSummary: the JSON record of one run (--json FILE). Its keys, types and units are documented in
// docs/json-schema.md, whose version is kSchemaVersion: every key is lower case with underscores, counts are
// integers, flags are booleans, times are in seconds, memory in bytes; a number that is not finite is null.
//
// The constructor records the schema version, radwalk's version and git describe, the command and its
// arguments and the library versions; commands add their counts, options and results through json(); stages are
// timed in the order they ran; write() adds the peak memory and the warnings and writes atomically.
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/solution.h"

namespace radwalk {

class RunSummary {
 public:
  // Version of the layout documented in docs/json-schema.md; raised whenever a key changes meaning or type.
  static constexpr int kSchemaVersion = 2;

  RunSummary(std::string command, const std::vector<std::string>& arguments);

  // json()["key"] = value, for counts, options and results.
  nlohmann::json& json() { return json_; }
  // Records the wall time of a named stage under timings_s ("load", "patch", "form_factors", "solve", "write").
  // The name is the key, with any space written as '_'.
  void add_timing(const std::string& stage, double seconds);
  void add_warning(const std::string& warning);

  // Writes the summary to path (atomically; "-": to standard output, core/standard_output.h), adding peak memory and
  // the warnings.
  void write(const std::string& path);

 private:
  nlohmann::json json_;
  std::vector<std::string> warnings_;
};

// Versions of the libraries radwalk was built with (eigen, embree, vtk).
nlohmann::json library_versions();

// `git describe --always --dirty` of the source tree radwalk was built from, at build time; "unknown" when it was
// not built from a git checkout.
const char* git_describe();

// A solver's result (deterministic, random walk or path tracer) as the summary's "solution" object: method,
// status, message, iterations, residual (null when not computed), residual_history, walks_total, steps, seconds and
// info (solution_info_json).
nlohmann::json solution_json(const Solution& solution);

// Solution::info with the keys that the schema lists as counts written as integers and those it lists as flags
// as booleans (a value that is not a whole number stays a number); every other value is a number.
nlohmann::json solution_info_json(const std::map<std::string, double>& info);

}  // namespace radwalk
