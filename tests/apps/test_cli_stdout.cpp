// End-to-end: `--csv -` and `--json -` write to standard output (core/standard_output.h). The stream read from the
// pipe is exactly the CSV or JSON, byte for byte what the same run writes to a file (the results' lines go to
// stderr then); two outputs to '-' are refused in one line; a failed write (a full device, a closed pipe) is one
// error line on stderr, after the results' lines, and exit 2, never a silent death by SIGPIPE.
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "radwalk_runner.h"

namespace fs = std::filesystem;

namespace {

fs::path scratch() { return scratch_dir("cli_stdout_test"); }

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct Split {
  int exit_code;
  std::string out, err;  // stdout, stderr: apart
};

// Runs `radwalk -q ARGS` with stdout read from a pipe and stderr into a file.
Split run_split(const std::string& args) {
  const fs::path err = scratch() / "stderr.txt";
  const std::string cmd = std::string(RADWALK_BINARY) + " -q " + args + " 2>" + err.string();
  Split r{-1, {}, {}};
  FILE* pipe = popen(cmd.c_str(), "r");
  REQUIRE(pipe != nullptr);
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0) r.out.append(buf, n);
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = read_text(err);
  return r;
}

// The rows of a CSV text, split at commas (radwalk's CSV has no quoted cells).
std::vector<std::vector<std::string>> csv_rows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::string cell;
    std::istringstream l(line);
    while (std::getline(l, cell, ',')) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    rows.push_back(cells);
  }
  return rows;
}

long count_lines(const std::string& s) { return static_cast<long>(std::count(s.begin(), s.end(), '\n')); }

// The last line of a text that ends in a newline.
std::string last_line(const std::string& s) {
  const std::size_t end = s.size() - (s.empty() ? 0 : 1);
  const std::size_t begin = s.rfind('\n', end == 0 ? 0 : end - 1);
  return s.substr(begin == std::string::npos ? 0 : begin + 1);
}

// The number of "radwalk: error:" lines in a text.
long error_lines(const std::string& s) {
  long n = 0;
  for (std::size_t at = s.find("radwalk: error:"); at != std::string::npos; at = s.find("radwalk: error:", at + 1))
    ++n;
  return n;
}

}  // namespace

TEST_CASE("radwalk --csv -: every command's CSV on stdout is the file's CSV, the results' lines on stderr",
          "[cli][stdout]") {
  const std::string cube = source("meshes/cube.obj");
  const std::vector<std::string> commands = {
      "patch " + cube + " --max-edge 0.5 -o " + (scratch() / "patches.vtp").string(),
      "formfactors " + cube + " --rays 200",
      "solve " + cube + " --rays 200",
      "solve " + cube + " --rays 200 --solver random-walk --walks-per-patch 20",
      "compare " + cube + " --rays 100 --estimators gather-collision --walks-per-patch 10 --runs 2",
      "pathtrace " + cube + " --spp 2",
  };
  for (const std::string& command : commands) {
    INFO("radwalk " << command);
    const fs::path file = scratch() / "file.csv";
    const Split piped = run_split(command + " --csv -");
    INFO("stderr: " << piped.err);
    REQUIRE(piped.exit_code == 0);
    const Split to_file = run_split(command + " --csv " + file.string());
    REQUIRE(to_file.exit_code == 0);
    // The results' lines moved from stdout to stderr (with timings, so compared by count and start).
    REQUIRE(!to_file.out.empty());
    CHECK(count_lines(piped.err) == count_lines(to_file.out) + count_lines(to_file.err));
    CHECK(piped.err.find(to_file.out.substr(0, 12)) != std::string::npos);
    // Stdout is the file's table, cell for cell but for compare's timings.
    const auto rows = csv_rows(piped.out), file_rows = csv_rows(read_text(file));
    REQUIRE(rows.size() >= 2);
    REQUIRE(rows.size() == file_rows.size());
    CHECK(rows[0][0] == "patch");
    for (std::size_t i = 0; i < rows.size(); ++i) {
      REQUIRE(rows[i].size() == rows[0].size());
      REQUIRE(file_rows[i].size() == rows[0].size());
      for (std::size_t k = 0; k < rows[0].size(); ++k)
        if (rows[0][k] != "seconds" && rows[0][k] != "efficiency") CHECK(rows[i][k] == file_rows[i][k]);
    }
  }
}

TEST_CASE("radwalk --json -: the JSON summary on stdout parses and is the whole of stdout", "[cli][stdout]") {
  const std::string cube = source("meshes/cube.obj");
  const std::vector<std::string> commands = {
      "check " + cube,
      "solve " + cube + " --rays 200",
      "measure " + cube + " --rays 200 --response patches:0 --method direct",
      "pathtrace " + cube + " --spp 2",
  };
  for (const std::string& command : commands) {
    INFO("radwalk " << command);
    const Split r = run_split(command + " --json -");
    INFO("stderr: " << r.err);
    REQUIRE(r.exit_code == 0);
    nlohmann::json j;
    REQUIRE_NOTHROW(j = nlohmann::json::parse(r.out));
    CHECK(j["schema_version"] == 2);
    CHECK(j.contains("timings_s"));
  }
  // With --json - and --csv FILE both are written, stdout still only the JSON.
  const fs::path csv = scratch() / "with_json.csv";
  const Split both = run_split("solve " + cube + " --rays 200 --json - --csv " + csv.string());
  REQUIRE(both.exit_code == 0);
  CHECK(nlohmann::json::parse(both.out)["patches"] == static_cast<long>(csv_rows(read_text(csv)).size()) - 1);
  // A refused scene: the summary saying so still goes to stdout, the error to stderr.
  const fs::path bad = scratch() / "bad.obj";
  std::ofstream(bad) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n";
  const Split refused = run_split("solve " + bad.string() + " --json -");
  CHECK(refused.exit_code == 2);
  CHECK(nlohmann::json::parse(refused.out)["refused"] == true);
  CHECK(refused.err.find("radwalk: error:") != std::string::npos);
}

TEST_CASE("radwalk: two outputs to '-' are refused in one line, before anything is read", "[cli][stdout]") {
  const std::string cube = source("meshes/cube.obj");
  const Run r = run("solve " + cube + " --json - --csv -");
  CHECK(r.exit_code == 2);
  CHECK(r.out ==
        "radwalk: error: --csv - and --json -: only one output can go to standard output; give the other a file "
        "name\n");
  // Other outputs are files: '-' does not end in their extension.
  const Run vtp = run("solve " + cube + " -o -");
  CHECK(vtp.exit_code == 2);
  CHECK(count_lines(vtp.out) == 1);
  CHECK(vtp.out.find("must end in .vtp") != std::string::npos);
}

TEST_CASE("radwalk --csv -: a write to a full device or a closed pipe fails in one line with exit 2", "[cli][stdout]") {
  const std::string cube = source("meshes/cube.obj");
  if (fs::exists("/dev/full")) {
    const fs::path err = scratch() / "full.txt";
    const std::string cmd = std::string(RADWALK_BINARY) + " -q solve " + cube + " --rays 100 --csv - >/dev/full 2>" +
                            err.string();
    const int status = std::system(cmd.c_str());
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 2);
    // The results' lines (on stderr since stdout carries the CSV), then the one error line.
    const std::string text = read_text(err);
    INFO(text);
    CHECK(error_lines(text) == 1);
    CHECK(last_line(text) == "radwalk: error: standard output: write failed (No space left on device)\n");
  }
  // A pipe whose reader is gone before the first byte: EPIPE, not SIGPIPE.
  int fds[2];
  REQUIRE(::pipe(fds) == 0);
  ::close(fds[0]);
  const fs::path err = scratch() / "epipe.txt";
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    ::dup2(fds[1], STDOUT_FILENO);
    const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(e, STDERR_FILENO);
    ::signal(SIGPIPE, SIG_DFL);
    const std::string scene = cube;
    ::execl(RADWALK_BINARY, RADWALK_BINARY, "-q", "solve", scene.c_str(), "--rays", "100", "--json", "-",
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::close(fds[1]);
  int status = 0;
  REQUIRE(::waitpid(pid, &status, 0) == pid);
  INFO(read_text(err));
  REQUIRE(WIFEXITED(status));  // not killed by SIGPIPE
  CHECK(WEXITSTATUS(status) == 2);
  const std::string text = read_text(err);
  CHECK(error_lines(text) == 1);
  CHECK(last_line(text) == "radwalk: error: standard output: write failed (Broken pipe: the reader closed the pipe "
                           "before the end; what it read is incomplete)\n");
}
