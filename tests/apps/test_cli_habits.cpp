// End-to-end: the command-line habits. Mistyped commands, options and choices get "did you mean" and point at
// the command's own help; output names whose extension does not match what is written are refused before
// anything is read; options the chosen method ignores are warned about; progress lines appear when stderr is a
// file, and not with -q.
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>

#include "radwalk_runner.h"

namespace fs = std::filesystem;

namespace {

fs::path scratch() { return scratch_dir("cli_habits_test"); }

// The program's one line of output, which must be an error with exit code 2.
std::string one_error(const std::string& args) {
  const Run r = run(args);
  INFO("radwalk " << args << " -> exit " << r.exit_code << ": " << r.out);
  CHECK(r.exit_code == 2);
  CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
  return r.out;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs `ENV radwalk ARGS` without --quiet, stderr to a file, stdout dropped; returns the exit code.
int run_with_stderr(const std::string& env, const std::string& args, const fs::path& err) {
  const std::string cmd = env + " " + RADWALK_BINARY + " " + args + " >/dev/null 2>" + err.string();
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

TEST_CASE("radwalk: a mistyped command or option says what was meant and points at the command's help", "[cli]") {
  const std::string cube = source("meshes/cube.obj");
  CHECK(one_error("solv " + cube) ==
        "radwalk: error: unknown command 'solv' (did you mean 'solve'?); see 'radwalk --help'\n");
  CHECK(one_error("solve " + cube + " --max-egde 25") ==
        "radwalk: error: unknown option '--max-egde' (did you mean '--max-edge'?); see 'radwalk solve --help'\n");
  CHECK(one_error("pathtrace " + cube + " --sp=4") ==
        "radwalk: error: unknown option '--sp' (did you mean '--spp'?); see 'radwalk pathtrace --help'\n");
  CHECK(one_error("") ==
        "radwalk: error: a command is required: check, patch, formfactors, solve, exchange, compare, measure or "
        "pathtrace; "
        "see 'radwalk --help'\n");
  // Nothing near: no suggestion; other parse errors keep their own words and point at the help.
  CHECK(one_error("solve " + cube + " --zzzzzz") ==
        "radwalk: error: unknown option '--zzzzzz'; see 'radwalk solve --help'\n");
  CHECK(one_error("formfactors " + cube + " --rays abc") ==
        "radwalk: error: --rays: expected a positive number, got 'abc'; see 'radwalk formfactors --help'\n");
  // Negative numbers are values, not options.
  CHECK(run("pathtrace " + cube + " --spp 2 --image " + (scratch() / "neg.png").string() +
            " --width 4 --height 4 --camera 0.5 0.5 -3 0.5 0.5 0.5 0 1 0 40")
            .exit_code == 0);
}

TEST_CASE("radwalk: an unknown value of a choice option gets the nearest choice, or the list", "[cli]") {
  const std::string cube = source("meshes/cube.obj");
  CHECK(one_error("solve " + cube + " --solver gauss-seidl") ==
        "radwalk: error: --solver: unknown value 'gauss-seidl' (did you mean 'gauss-seidel'?); "
        "see 'radwalk solve --help'\n");
  CHECK(one_error("pathtrace " + cube + " --integrator ne") ==
        "radwalk: error: --integrator: unknown value 'ne' (did you mean 'nee'?); see 'radwalk pathtrace --help'\n");
  CHECK(one_error("solve " + cube + " --solver xyz") ==
        "radwalk: error: --solver: unknown value 'xyz' (expected one of auto, direct, jacobi, gauss-seidel, "
        "southwell, gmres or random-walk); see 'radwalk solve --help'\n");
}

TEST_CASE("radwalk: an output whose extension does not match what is written is refused before reading the scene",
          "[cli]") {
  // The scene does not exist: the refusal of the name comes first, so nothing was loaded or computed.
  const std::string missing = (scratch() / "no-such-scene.obj").string();
  struct Case {
    std::string args, message;
  };
  for (const Case& c : std::vector<Case>{
           {"solve " + missing + " -o out.png", "out.png: the file written is VTK XML PolyData, so its name must end in .vtp"},
           {"formfactors " + missing + " -o F.csv", "F.csv: the file written is a Matrix Market (.mtx) or binary CSR (.npz) matrix, so its name must end in .mtx or .npz"},
           {"formfactors " + missing + " --vtp d.csv", "d.csv: the file written is VTK XML PolyData"},
           {"solve " + missing + " --csv B.txt", "B.txt: the file written is CSV, so its name must end in .csv"},
           {"check " + missing + " --json S.txt", "S.txt: the file written is a JSON summary, so its name must end in .json"},
           {"compare " + missing + " -o c.csv", "c.csv: the file written is VTK XML PolyData"},
           {"pathtrace " + missing + " --image i.jpg", "i.jpg: the file written is a PNG (sRGB) or OpenEXR (linear) image, so its name must end in .png or .exr"},
           {"patch " + missing + " -o p.stl", "p.stl: the file written is VTK XML PolyData or OBJ (+ .mtl), so its name must end in .vtp or .obj"},
           {"solve " + missing + " -o /nonexistent-dir/b.vtp", "no directory /nonexistent-dir"},
       }) {
    const std::string out = one_error(c.args);
    INFO(c.args << " -> " << out);
    CHECK(out.rfind("radwalk: error: ", 0) == 0);
    CHECK(out.find(c.message) != std::string::npos);
    CHECK(out.find("no such file") == std::string::npos);
  }
  // Matching names pass (the scene's absence is then the error).
  const std::string b = (scratch() / "b").string();  // the error's JSON summary is written: not into the cwd
  CHECK(run("solve " + missing + " -o " + b + ".vtp --csv " + b + ".csv --json " + b + ".json").out.find("no such file") !=
        std::string::npos);
  CHECK(run("patch " + missing + " -o p.obj").out.find("no such file") != std::string::npos);
}

TEST_CASE("radwalk: options the chosen method cannot honour are refused in one line naming them", "[cli]") {
  const Run r = run("solve " + source("meshes/cube.obj") + " --walk shoot --solver direct --tol 1e-3 --refine-steps 2");
  INFO(r.out);
  CHECK(r.exit_code == 2);
  CHECK(r.out.rfind("radwalk: error: ", 0) == 0);
  CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
  CHECK(r.out.find("--walk does not apply here (used only with --solver random-walk): remove it") != std::string::npos);
  CHECK(r.out.find("--tol does not apply here (used only by the iterative solvers") != std::string::npos);
  CHECK(r.out.find("--refine-steps does not apply here (used only with --refine)") != std::string::npos);

  // Options that apply pass; several of one kind share a clause.
  CHECK(run("solve " + source("meshes/cube.obj") + " --solver jacobi --tol 1e-6").exit_code == 0);
  const Run pt = run("pathtrace " + source("meshes/cube.obj") + " --spp 2 --width 8 --height 8");
  CHECK(pt.exit_code == 2);
  CHECK(pt.out.find("radwalk: error: --width and --height do not apply here (used only with --image): remove them") !=
        std::string::npos);
  const Run ray =
      run("solve " + source("meshes/cube.obj") + " --solver random-walk --kernel ray --walks-per-patch 10 --rays 10");
  CHECK(ray.out.find("radwalk: error: --rays does not apply here (used only for form factors, which --kernel ray "
                     "does not use)") != std::string::npos);
  // --hierarchical stores no form factors and has its own tolerance; its options need it.
  const Run hier = run("solve " + source("meshes/cube.obj") + " --hierarchical --rays 10 --tol 1e-3");
  CHECK(hier.exit_code == 2);
  CHECK(hier.out.find("--rays does not apply here (used only for form factors, which --hierarchical does not use)") !=
        std::string::npos);
  CHECK(hier.out.find("--tol does not apply here") != std::string::npos);
  CHECK(run("solve " + source("meshes/cube.obj") + " --hierarchical-levels 3").out.find(
            "--hierarchical-levels does not apply here (used only with --hierarchical, or --target-error on its "
            "default route, the hierarchical one)") != std::string::npos);
  CHECK(run("solve " + source("meshes/cube.obj") + " --hierarchical --solver jacobi").out.find(
            "--hierarchical is a solver of its own") != std::string::npos);
  // measure: the kernel of a method that does not walk (it ran on the matrix kernel before, silently).
  const Run importance = run("measure " + source("meshes/cube.obj") +
                             " --response patches:0 --method importance-gather --kernel ray --walks 100");
  CHECK(importance.exit_code == 2);
  CHECK(importance.out.find("--kernel does not apply here (used only by the walk methods") != std::string::npos);
  CHECK(run("measure " + source("meshes/cube.obj") + " --response patches:0 --method gather-expected-value "
            "--kernel ray --walks 100").exit_code == 0);
}

TEST_CASE("radwalk: progress lines when stderr is a file, none for quick stages or with -q", "[cli]") {
  const std::string args = "solve " + source("meshes/cornell_box.obj") + " --max-edge 50 --rays 4000 --threads 1";
  const fs::path err = scratch() / "progress.txt";
  // Every 0.05 s instead of every 5 s, so that a short run shows the lines a long one would.
  REQUIRE(run_with_stderr("RADWALK_PROGRESS_INTERVAL=0.05", args, err) == 0);
  const std::string text = read_text(err);
  INFO(text);
  const std::regex line(R"(radwalk: form factors [0-9]+% \([0-9]+/1070\), [0-9.]+ s elapsed, about [0-9.]+ s left\n)");
  CHECK(std::regex_search(text, line));
  CHECK(text.find("radwalk: form factors done in ") != std::string::npos);
  CHECK(text.find('\r') == std::string::npos);

  // The default interval (5 s): a run whose form factors take about 0.05 s (160,000 rays; far below 5 s even on a
  // loaded machine) prints no progress line at all.
  const std::string quick = "solve " + source("meshes/cornell_box.obj") + " --max-edge 100 --rays 500 --threads 1";
  REQUIRE(run_with_stderr("", quick, err) == 0);
  CHECK(read_text(err).find("form factors done") == std::string::npos);
  CHECK(read_text(err).find("radwalk: form factors ") == std::string::npos);

  // The error estimate's block solves (solve/block_jacobi.h) report as iterations: about 0.1 s of sweeps here,
  // 5-6 s each on a city block of 139,808 patches, where they printed nothing; every 2 ms shows their lines.
  REQUIRE(run_with_stderr("RADWALK_PROGRESS_INTERVAL=0.002", args, err) == 0);
  const std::string estimate = read_text(err);
  INFO(estimate);
  const std::string label = "radwalk: error estimate: the propagation of the form factors' noise, sweeps";
  CHECK(std::regex_search(estimate, std::regex(label + R"( [0-9]+% \([0-9]+/[0-9]+\), [0-9.]+ s elapsed)")));
  CHECK(estimate.find(label + " done in ") != std::string::npos);

  // -q silences progress whatever the interval.
  REQUIRE(run_with_stderr("RADWALK_PROGRESS_INTERVAL=0.05", args + " -q", err) == 0);
  CHECK(read_text(err).find("form factors") == std::string::npos);
}
