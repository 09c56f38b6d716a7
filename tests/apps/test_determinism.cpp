// Determinism across thread counts (docs/reliability.md "Determinism"): every output file of every
// command is the same byte for byte with --threads 1 and --threads 2, except the documented fields that record how
// a run went rather than what it computed, which are removed before the comparison:
//   JSON: arguments, threads, timings_s, peak_memory_bytes, every key naming seconds or a rate per second
//         (solution.seconds, image.seconds, rays_per_second, estimators.*.seconds, ...), compare's
//         estimators.*.efficiency (1 / (var x seconds)), and the output names
//         (image.file, progressive.pvd);
//   .vtp field data: command_line and every entry naming seconds (seconds_<stage>, solve_seconds);
//   compare --csv: the columns seconds and efficiency (1 / (var x seconds)).
#include <nlohmann/json.hpp>
#include <regex>

#include "radwalk_runner.h"
#include "run_id_reader.h"

namespace fs = std::filesystem;

namespace {

bool timing_key(const std::string& key) {
  return key.find("seconds") != std::string::npos || key.find("per_second") != std::string::npos ||
         key == "efficiency";
}

void strip_json(nlohmann::json& j) {
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end();) {
      if (timing_key(it.key())) it = j.erase(it);
      else strip_json(*it++);
    }
  } else if (j.is_array()) {
    for (auto& v : j) strip_json(v);
  }
}

// The bytes compared: the file with its documented run-dependent fields removed.
std::string comparable(const fs::path& path) {
  const std::string text = file_text(path);
  const std::string ext = path.extension().string();
  if (ext == ".json") {
    nlohmann::json j = nlohmann::json::parse(text);
    for (const char* key : {"arguments", "threads", "timings_s", "peak_memory_bytes"}) j.erase(key);
    if (j.contains("image")) j["image"].erase("file");
    if (j.contains("progressive")) j["progressive"].erase("pvd");
    strip_json(j);
    return j.dump(1);
  }
  if (ext == ".vtp") {
    static const std::regex run_dependent(
        R"re(<(Array|DataArray) [^>]*Name="(command_line|[A-Za-z_]*seconds[A-Za-z_]*)"[^>]*>[^<]*</\1>\s*)re");
    return std::regex_replace(text, run_dependent, "");
  }
  if (ext == ".csv" && text.rfind("patch,estimator,", 0) == 0) {
    // compare's long table: drop the columns seconds and efficiency.
    std::stringstream in(text);
    std::string line, out;
    std::vector<bool> keep;
    while (std::getline(in, line)) {
      std::vector<std::string> cells;
      std::stringstream ss(line);
      for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
      if (keep.empty())
        for (const std::string& c : cells) keep.push_back(c != "seconds" && c != "efficiency");
      for (std::size_t k = 0; k < cells.size() && k < keep.size(); ++k)
        if (keep[k]) out += cells[k] + ',';
      out += '\n';
    }
    return out;
  }
  return text;
}

// Runs `args` (which name their outputs in the directory OUT/) with --threads 1 and --threads 2 and compares
// every file written; returns how many.
std::size_t compare_thread_counts(const std::string& name, const std::string& args) {
  const fs::path root = scratch_dir("determinism") / name;
  fs::remove_all(root);
  std::map<std::string, std::string> files[2];
  for (int threads = 1; threads <= 2; ++threads) {
    const fs::path dir = root / std::to_string(threads);
    fs::create_directories(dir);
    const std::string cmd = std::regex_replace(args, std::regex("OUT/"), dir.string() + "/") + " --threads " +
                            std::to_string(threads);
    const Run r = run(cmd);
    INFO(cmd << "\n" << r.out);
    REQUIRE(r.exit_code == 0);
    for (const auto& e : fs::recursive_directory_iterator(dir))
      if (e.is_regular_file()) files[threads - 1][fs::relative(e.path(), dir).string()] = comparable(e.path());
  }
  REQUIRE(files[0].size() == files[1].size());
  for (const auto& [file, bytes] : files[0]) {
    INFO(name << ": " << file);
    REQUIRE(files[1].count(file));
    const std::string& other = files[1].at(file);
    if (bytes == other) continue;
    std::size_t at = 0;
    while (at < bytes.size() && at < other.size() && bytes[at] == other[at]) ++at;
    const std::size_t from = at > 200 ? at - 200 : 0;
    FAIL_CHECK("differ at byte " << at << " of " << bytes.size() << ":\n1 thread: " << bytes.substr(from, 300)
                                 << "\n2 threads: " << other.substr(from, 300));
  }
  return files[0].size();
}

}  // namespace

TEST_CASE("every output of every command is the same with 1 and 2 threads", "[determinism]") {
  const std::string scene = source("meshes/cornell_box.obj") + " --max-edge 150 --seed 3 ";
  const std::string outs = "-o OUT/out.vtp --csv OUT/out.csv --json OUT/out.json";
  struct Case {
    std::string name, args;
    std::size_t files;
  };
  const std::vector<Case> cases = {
      {"check", "check " + scene.substr(0, scene.find(" --max-edge")) + " --json OUT/check.json", 1},
      {"patch-vtp", "patch " + scene + "-o OUT/p.vtp --csv OUT/p.csv --json OUT/p.json", 3},
      {"patch-obj", "patch " + scene + "-o OUT/p.obj", 2},
      {"formfactors", "formfactors " + scene + "-o OUT/F.mtx --vtp OUT/ff.vtp --csv OUT/ff.csv --json OUT/ff.json", 4},
      {"solve-direct", "solve " + scene + "--solver direct " + outs, 3},
      {"solve-jacobi", "solve " + scene + "--solver jacobi " + outs, 3},
      {"solve-gauss-seidel", "solve " + scene + "--solver gauss-seidel " + outs, 3},
      {"solve-southwell", "solve " + scene + "--solver southwell " + outs, 3},
      {"solve-gather", "solve " + scene + "--solver random-walk --walks-per-patch 50 " + outs, 3},
      {"solve-shoot", "solve " + scene + "--solver random-walk --walk shoot --estimator collision --particles 20000 " +
                          outs, 3},
      {"solve-ray-kernel", "solve " + scene + "--solver random-walk --kernel ray --walks-per-patch 20 " + outs, 3},
      {"solve-refine", "solve " + scene + "--refine 0.5 --refine-steps 1 " + outs, 3},
      {"solve-progressive", "solve " + scene + "--solver jacobi --progressive OUT/series " + outs, 3},
      {"solve-hierarchical", "solve " + scene + "--hierarchical --hierarchical-rays 20000 " + outs, 3},
      {"solve-target-hierarchical",
       "solve " + scene + "--target-error 0.05 --rays 200 --discretisation-directions 4 " + outs, 3},
      {"solve-target-rays",
       "solve " + scene + "--target-error 0.2 --rays 100 --hierarchical-transport rays --discretisation-directions 4 " +
           outs, 3},
      {"solve-target-uniform",
       "solve " + scene + "--target-error 0.05 --target-route uniform --rays 200 --discretisation-directions 4 " + outs,
       3},
      {"compare", "compare " + scene + "--walks-per-patch 10 --runs 2 -o OUT/c.vtp --csv OUT/c.csv --json OUT/c.json",
       3},
      {"pathtrace", "pathtrace " + scene + "--spp 4 --width 24 --height 16 --image OUT/i.png " + outs, 4},
      {"pathtrace-exr", "pathtrace " + scene + "--spp 4 --width 24 --height 16 --image OUT/i.exr --json OUT/i.json", 3},
      {"pathtrace-light", "pathtrace " + scene + "--integrator light --spp 4 --width 24 --height 16 --image OUT/l.png " +
                              outs, 4},
  };
  for (const Case& c : cases) {
    const std::size_t files = compare_thread_counts(c.name, c.args);
    INFO(c.name);
    // solve-progressive also writes its series (step_*.vtp and the .pvd).
    if (c.name == "solve-progressive") CHECK(files > c.files + 2);
    else CHECK(files == c.files);
  }
}
