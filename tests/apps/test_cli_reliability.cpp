// End-to-end reliability checks of the radwalk program (docs/reliability.md): the run id in every output, memory
// bounds refused or kept up front (O4), real processes killed while writing an output (P2), outputs under a
// file-size limit, refused outputs never written, progressive series replaced only when complete, and the limits
// on path lengths.
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include "core/atomic_write.h"
#include "radwalk_runner.h"
#include "run_id_reader.h"
#include "support/reference_problems.h"

namespace fs = std::filesystem;

namespace {

fs::path scratch() { return scratch_dir("cli_reliability"); }

// Runs one of each command writing every kind of output into dir; returns file name -> run id.
std::map<std::string, std::string> outputs_of(const fs::path& dir, const std::string& scene, int seed) {
  fs::create_directories(dir);
  const std::string common = scene + " --max-edge 300 --seed " + std::to_string(seed) + " ";
  const auto out = [&](const std::string& name) { return (dir / name).string(); };
  const std::vector<std::string> commands = {
      "formfactors " + common + "-o " + out("F.mtx") + " --vtp " + out("ff.vtp") + " --csv " + out("ff.csv") +
          " --json " + out("ff.json"),
      "patch " + common + "-o " + out("p.obj") + " --csv " + out("p.csv") + " --json " + out("p.json"),
      "solve " + common + "-o " + out("s.vtp") + " --csv " + out("s.csv") + " --json " + out("s.json") +
          " --paraview-state " + out("s.py"),
      "compare " + common + "--estimators gather-collision,shoot-absorption --walks-per-patch 4 --runs 2 -o " + out("c.vtp") +
          " --csv " + out("c.csv") + " --json " + out("c.json"),
      "pathtrace " + common + "--spp 2 --width 8 --height 8 --image " + out("i.png") + " -o " + out("t.vtp") +
          " --csv " + out("t.csv"),
      "pathtrace " + common + "--spp 2 --width 8 --height 8 --image " + out("i.exr"),
      "check " + scene + " --seed " + std::to_string(seed) + " --json " + out("check.json"),
  };
  for (const std::string& c : commands) {
    const Run r = run(c);
    INFO(c << "\n" << r.out);
    REQUIRE(r.exit_code == 0);
  }
  std::map<std::string, std::string> ids;
  for (const auto& entry : fs::directory_iterator(dir)) ids[entry.path().filename().string()] = run_id_in(entry.path());
  return ids;
}

// The outputs written by one command (by name), whose ids must agree.
const std::vector<std::vector<std::string>> kRuns = {{"F.mtx", "ff.vtp", "ff.csv", "ff.json"},
                                                     {"p.obj", "p.mtl", "p.csv", "p.json"},
                                                     {"s.vtp", "s.csv", "s.json", "s.py"},
                                                     {"c.vtp", "c.csv", "c.json"},
                                                     {"i.png", "t.vtp", "t.csv"},
                                                     {"i.exr", "i.se.exr"},
                                                     {"check.json"}};

// True when the files were written by one run: all carry the same run id.
bool one_run(const std::vector<fs::path>& files) {
  std::set<std::string> ids;
  for (const fs::path& f : files) ids.insert(run_id_in(f));
  return ids.size() == 1 && !ids.begin()->empty();
}

}  // namespace

TEST_CASE("every output carries the run id: equal for the same run, different for another seed or input",
          "[cli][run_id]") {
  const fs::path dir = scratch() / "run_id";
  fs::remove_all(dir);
  // A copy of the Cornell box, run as it is and then with one MTL number longer by a digit: the same path and
  // options, another input.
  const fs::path other = dir / "scene";
  fs::create_directories(other);
  fs::copy_file(source("meshes/cornell_box.obj"), other / "cornell_box.obj");
  fs::copy_file(source("meshes/cornell_box.mtl"), other / "cornell_box.mtl");
  const std::string scene = source("meshes/cornell_box.obj"), copy = (other / "cornell_box.obj").string();
  const auto a = outputs_of(dir / "a", scene, 1), again = outputs_of(dir / "again", scene, 1),
             seed = outputs_of(dir / "seed", scene, 2), copied = outputs_of(dir / "copied", copy, 1);
  std::string mtl = file_text(other / "cornell_box.mtl");
  const std::size_t kd = mtl.find("Kd ");
  REQUIRE(kd != std::string::npos);
  mtl.insert(mtl.find('\n', kd), "1");  // the Kd's last component gains a digit
  std::ofstream(other / "cornell_box.mtl") << mtl;
  const auto input = outputs_of(dir / "input", copy, 1);

  std::size_t files = 0;
  for (const auto& names : kRuns)
    for (const std::string& name : names) {
      INFO(name);
      ++files;
      REQUIRE(a.count(name));
      const std::string id = a.at(name);
      CHECK(id.size() == 16);
      CHECK(id.find_first_not_of("0123456789abcdef") == std::string::npos);
      CHECK(id == a.at(names.front()));  // one id per run, in every file it wrote
      CHECK(again.at(name) == id);       // the same run twice: the same id
      CHECK(seed.at(name) != id);        // another seed
      CHECK(input.at(name) != copied.at(name));  // another input byte
      CHECK(copied.at(name) != id);              // another scene path (recorded in the outputs)
    }
  CHECK(files == a.size());  // every file written is listed above (nothing without an id)
  // Ids of different commands differ.
  std::set<std::string> per_command;
  for (const auto& names : kRuns) per_command.insert(a.at(names.front()));
  CHECK(per_command.size() == kRuns.size());
}

TEST_CASE("a .vtp and a .csv of two different runs left side by side are detected as mixed", "[cli][run_id]") {
  // P2: a run killed between two writes leaves a new .vtp beside an old .csv.
  const fs::path dir = scratch() / "mixed";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string scene = source("meshes/cornell_box.obj") + " --max-edge 300";
  const fs::path vtp = dir / "B.vtp", csv = dir / "B.csv";
  REQUIRE(run("solve " + scene + " -o " + vtp.string() + " --csv " + csv.string()).exit_code == 0);
  CHECK(one_run({vtp, csv}));
  // The next run (another seed) "killed" after its .vtp: only -o written.
  REQUIRE(run("solve " + scene + " --seed 7 -o " + vtp.string()).exit_code == 0);
  CHECK_FALSE(one_run({vtp, csv}));
  // And once the run completes, the pair is consistent again.
  REQUIRE(run("solve " + scene + " --seed 7 -o " + vtp.string() + " --csv " + csv.string()).exit_code == 0);
  CHECK(one_run({vtp, csv}));
}

TEST_CASE("the run id ignores --threads, --quiet and output names, and records every other option",
          "[cli][run_id]") {
  const fs::path dir = scratch() / "options";
  fs::create_directories(dir);
  const std::string scene = source("meshes/cornell_box.obj") + " --max-edge 300";
  const auto id = [&](const std::string& options) {
    const fs::path json = dir / ("r" + std::to_string(std::rand()) + ".json");
    const Run r = run("solve " + scene + " --json " + json.string() + " " + options);
    INFO(r.out);
    REQUIRE(r.exit_code == 0);
    return run_id_in(json);
  };
  const std::string base = id("");
  CHECK(id("--threads 1") == base);
  CHECK(id("--threads 2 -q") == base);
  CHECK(id("--rays 999") != base);
  CHECK(id("--solver gauss-seidel") != base);
  CHECK(id("--reciprocity") != base);
}

TEST_CASE("O4: an image too large for memory is refused up front, naming --width/--height and the bytes",
          "[cli][limits]") {
  const fs::path png = scratch() / "huge.png";
  const Run r = run("pathtrace " + source("meshes/cube.obj") + " --image " + png.string() +
                    " --width 100000 --height 100000");
  INFO(r.out);
  CHECK(r.exit_code == 2);
  CHECK(r.out.find("--width 100000 --height 100000") != std::string::npos);
  CHECK(r.out.find("480000000000 bytes") != std::string::npos);
  CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
  CHECK_FALSE(fs::exists(png));
  // The largest accepted size is 2^26 pixels: 8192 x 8193 is refused, without loading the scene.
  CHECK(run("pathtrace no_such_scene.obj --image " + png.string() + " --width 8192 --height 8193").out.find(
            "--width 8192 --height 8193") != std::string::npos);
}

TEST_CASE("O4: form-factor memory does not grow with the rays of one patch", "[cli][limits]") {
  // 16 bytes per ray of a patch made --rays 2e9 need 32 GB. Two facing unit squares, 3 x 2^20 rays each (three
  // chunks of front hits): the peak memory of the process must stay below 8 bytes per ray above that of a run
  // with 1000 rays (the old buffers held 24 to 32 bytes per ray of a row with one thread), and the estimate must
  // agree with the analytic F = 0.199824896 (C-11).
  const fs::path csv = scratch() / "rays.csv";
  const long rays = 3L << 20;
  const std::string scene = source("meshes/parallel_squares.obj") + " --threads 1 ";
  const double small = peak_kib("formfactors " + scene + "--rays 1000");
  const double large = peak_kib("formfactors " + scene + "--rays " + std::to_string(rays) + " --csv " + csv.string());
  INFO("peak " << small << " KiB with 1000 rays, " << large << " KiB with " << rays << " rays");
  CHECK((large - small) * 1024 < 8.0 * rays);
  // Row 0's sum is F_01 (the only other patch): a binomial count (stratification only lowers the variance),
  // two-sided at alpha = 1e-6: |F - F_ref| <= 4.89 sd.
  std::ifstream in(csv);
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  std::vector<std::string> names, cells;
  std::stringstream hs(header), rs(row);
  for (std::string c; std::getline(hs, c, ',');) names.push_back(c);
  for (std::string c; std::getline(rs, c, ',');) cells.push_back(c);
  const auto col = [&](const std::string& name) {
    const auto it = std::find(names.begin(), names.end(), name);
    REQUIRE(it != names.end());
    return std::stod(cells[static_cast<std::size_t>(it - names.begin())]);
  };
  CHECK(col("rays") == rays);
  const double p = radwalk::test::kOpposite, sd = std::sqrt(p * (1 - p) / rays);
  CHECK(std::abs(col("row_sum") - p) <= 4.89 * sd);
}

namespace {

// Starts radwalk with args (stdout and stderr to /dev/null); returns its pid.
pid_t start(const std::string& args) {
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    const std::string cmd = "exec " + std::string(RADWALK_BINARY) + " -q " + args + " > /dev/null 2>&1";
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

std::vector<std::string> temporaries(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().find(".radwalk-tmp-") != std::string::npos) out.push_back(e.path().string());
  return out;
}

// Starts `patch` writing a large CSV over `csv` (which holds "old\n"), waits until its temporary appears, sends
// `signal`; returns whether the temporary was seen before the run ended (the kill then hit the write).
bool kill_while_writing(const fs::path& dir, const fs::path& csv, int signal) {
  std::ofstream(csv) << "old\n";
  const pid_t pid = start("patch " + source("meshes/cornell_box.obj") + " --max-edge 2 -o " +
                          (dir / "big.vtp").string() + " --csv " + csv.string());
  bool seen = false;
  int status = 0;
  for (;;) {
    for (const std::string& t : temporaries(dir))
      if (fs::path(t).filename().string().rfind(radwalk::temporary_prefix(csv.string()), 0) == 0) seen = true;
    if (seen) {
      ::kill(pid, signal);
      break;
    }
    if (waitpid(pid, &status, WNOHANG) == pid) return false;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  REQUIRE(waitpid(pid, &status, 0) == pid);
  // Killed by the signal (or, if the write had just finished, exited normally).
  CHECK((WIFSIGNALED(status) ? WTERMSIG(status) == signal : WEXITSTATUS(status) == 0));
  return true;
}

// The CSV is the old one or a complete new one (its header, then 1 row per patch, ending in a newline).
void check_old_or_complete(const fs::path& csv) {
  const std::string text = file_text(csv);
  if (text == "old\n") return;
  REQUIRE(text.rfind("patch,face,area", 0) == 0);
  CHECK(text.back() == '\n');
}

}  // namespace

TEST_CASE("P2: SIGTERM during a CLI output write leaves the old file and no temporary", "[cli][fault]") {
  const fs::path dir = scratch() / "sigterm";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path csv = dir / "big.csv";
  bool hit = false;
  for (int attempt = 0; attempt < 5 && !hit; ++attempt) {
    hit = kill_while_writing(dir, csv, SIGTERM);
    check_old_or_complete(csv);
    CHECK(temporaries(dir).empty());
  }
  CHECK(hit);  // the write takes about a second: the temporary was seen
  CHECK(file_text(csv) == "old\n");
  fs::remove_all(dir);
}

TEST_CASE("P2: kill -9 during a CLI output write leaves the old file, and the next run removes the temporary",
          "[cli][fault]") {
  const fs::path dir = scratch() / "sigkill";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path csv = dir / "big.csv";
  bool hit = false;
  for (int attempt = 0; attempt < 5 && !hit; ++attempt) {
    hit = kill_while_writing(dir, csv, SIGKILL);
    check_old_or_complete(csv);
  }
  REQUIRE(hit);
  CHECK(file_text(csv) == "old\n");
  CHECK_FALSE(temporaries(dir).empty());  // kill -9 cannot be caught: the temporary stays...
  const Run r = run("patch " + source("meshes/cube.obj") + " -o " + (dir / "cube.vtp").string() + " --csv " +
                    csv.string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  CHECK(temporaries(dir).empty());  // ...until the next run writing the same file removes it
  check_old_or_complete(csv);
  CHECK(file_text(csv) != "old\n");
  fs::remove_all(dir);
}

TEST_CASE("measure's run id follows its options: another method or response is another run", "[cli][run_id]") {
  const fs::path dir = scratch() / "measure_ids";
  fs::create_directories(dir);
  const std::string scene = source("meshes/cornell_box.obj") + " --max-edge 300 --rays 200 --seed 1";
  const auto id = [&](const std::string& args) {
    const fs::path json = dir / "m.json";
    const Run r = run("measure " + scene + " " + args + " --json " + json.string());
    INFO(args << " -> " << r.out);
    REQUIRE(r.exit_code == 0);
    return run_id_in(json);
  };
  const std::string base = id("--response material:white --method direct");
  CHECK(!base.empty());
  CHECK(id("--response material:white --method direct") == base);
  CHECK(id("--response material:white --method adjoint-direct") != base);
  CHECK(id("--response material:red --method direct") != base);
}

namespace {

// Runs a shell command line: exit code (-1 when killed by a signal) and merged stdout + stderr, as run().
Run run_shell(const std::string& command) {
  Run r{-1, {}};
  FILE* pipe = popen(("{ " + command + "; } 2>&1").c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), buf.size(), pipe)) r.out += buf.data();
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// Runs radwalk under a file-size limit of `kib` KiB (ulimit -f, as batch systems set it): exit code and merged
// output, as run().
Run run_limited(int kib, const std::string& args) {
  return run_shell("ulimit -f " + std::to_string(kib) + "; exec " + std::string(RADWALK_BINARY) + " --quiet " + args);
}

// The lines radwalk printed about the run ("radwalk: ..."), not the command's own report on stdout.
std::size_t lines_of(const std::string& text) {
  std::istringstream in(text);
  std::size_t lines = 0;
  for (std::string line; std::getline(in, line);) lines += line.rfind("radwalk:", 0) == 0;
  return lines;
}

// Every file under dir (recursively) with its content.
std::map<std::string, std::string> contents(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = file_text(e.path());
  return files;
}

}  // namespace

TEST_CASE("a file-size limit (ulimit -f) fails the write in one line naming the file, keeps the old file and "
          "leaves no temporary", "[cli][fault][limits]") {
  const fs::path dir = scratch() / "file_size_limit";
  fs::remove_all(dir);
  fs::create_directories(dir);
  // A stream writer (.vtp), then a writer that takes a file name (OpenEXR), each beyond a 64 KiB limit.
  const fs::path vtp = dir / "big.vtp", exr = dir / "big.exr";
  for (const fs::path& f : {vtp, exr}) std::ofstream(f) << "old\n";
  const std::vector<std::pair<fs::path, std::string>> cases = {
      {vtp, "patch " + source("meshes/cornell_box.obj") + " --max-edge 30 -o " + vtp.string()},
      {exr, "pathtrace " + source("meshes/cube.obj") + " --spp 2 --width 200 --height 200 --image " + exr.string()}};
  for (const auto& [file, args] : cases) {
    const Run r = run_limited(64, args);
    INFO(args << "\n" << r.out);
    CHECK(r.exit_code == 2);
    CHECK(lines_of(r.out) == 1);
    CHECK(r.out.find(file.string() + ": write failed: file size limit reached") != std::string::npos);
    CHECK(file_text(file) == "old\n");
    CHECK(temporaries(dir).empty());
  }
  // The same commands without the limit write them.
  for (const auto& [file, args] : cases) CHECK(run(args).exit_code == 0);
  CHECK(file_text(vtp) != "old\n");
  CHECK(fs::file_size(vtp) > 64 * 1024);
  CHECK(fs::file_size(exr) > 64 * 1024);
  fs::remove_all(dir);
}

TEST_CASE("a --json naming the scene's material library, directly or through a link, is refused and never written",
          "[cli][fault]") {
  const fs::path dir = scratch() / "json_refused";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string mtl = file_text(source("meshes/cube.mtl"));
  // A scene whose library is named like a JSON file, and a plain copy of the cube.
  std::string obj = file_text(source("meshes/cube.obj"));
  obj.replace(obj.find("mtllib cube.mtl"), 15, "mtllib lib.json");
  std::ofstream(dir / "odd.obj") << obj;
  std::ofstream(dir / "lib.json") << mtl;
  fs::copy_file(source("meshes/cube.obj"), dir / "cube.obj");
  fs::copy_file(source("meshes/cube.mtl"), dir / "cube.mtl");
  fs::create_symlink("cube.mtl", dir / "link.json");
  fs::create_symlink("cube.mtl", dir / "link.csv");
  const std::vector<std::pair<std::string, fs::path>> cases = {
      {"check " + (dir / "odd.obj").string() + " --json " + (dir / "lib.json").string(), dir / "lib.json"},
      {"patch " + (dir / "odd.obj").string() + " -o " + (dir / "p.vtp").string() + " --json " +
           (dir / "lib.json").string(), dir / "lib.json"},
      {"check " + (dir / "cube.obj").string() + " --json " + (dir / "link.json").string(), dir / "cube.mtl"},
      {"solve " + (dir / "cube.obj").string() + " --json " + (dir / "link.json").string(), dir / "cube.mtl"}};
  for (const auto& [args, library] : cases) {
    const Run r = run(args);
    INFO(args << "\n" << r.out);
    CHECK(r.exit_code == 2);
    CHECK(lines_of(r.out) == 1);
    CHECK(r.out.find("would overwrite the scene's material library") != std::string::npos);
    CHECK(file_text(library) == mtl);
    CHECK(fs::is_symlink(fs::symlink_status(dir / "link.json")));
    CHECK_FALSE(fs::exists(dir / "p.vtp"));
  }
  // Another output refused for naming the library: --json, which passed its checks, records the refusal.
  const Run r = run("patch " + (dir / "cube.obj").string() + " -o " + (dir / "p.vtp").string() + " --csv " +
                    (dir / "link.csv").string() + " --json " + (dir / "good.json").string());
  INFO(r.out);
  CHECK(r.exit_code == 2);
  CHECK(file_text(dir / "cube.mtl") == mtl);
  REQUIRE(fs::exists(dir / "good.json"));
  CHECK(file_text(dir / "good.json").find("\"refused\": true") != std::string::npos);
  CHECK(temporaries(dir).empty());
  fs::remove_all(dir);
}

TEST_CASE("progressive series: replaced only when the new one is complete, a failed run keeps the old one",
          "[cli][fault]") {
  const fs::path dir = scratch() / "progressive_replace";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path series = dir / "series";
  const std::string solve = "solve " + source("meshes/cube.obj") + " --rays 500 --solver jacobi --progressive " +
                            series.string();
  REQUIRE(run(solve + " --tol 1e-10").exit_code == 0);
  const auto old = contents(series);
  REQUIRE(old.size() > 3);  // solve.pvd and its steps
  // The new series cannot be written (a file-size limit below one step): the old one stays, whole.
  const Run failed = run_limited(1, solve + " --tol 1e-3");
  INFO(failed.out);
  CHECK(failed.exit_code == 2);
  CHECK(lines_of(failed.out) == 1);
  CHECK(failed.out.find("file size limit reached") != std::string::npos);
  CHECK(contents(series) == old);
  CHECK(temporaries(series).empty());
  // A shorter series that succeeds replaces it: every step file is in the collection, no earlier one is left.
  REQUIRE(run(solve + " --tol 1e-3").exit_code == 0);
  const auto now = contents(series);
  CHECK(now != old);
  CHECK(now.size() < old.size());
  const std::string pvd = now.at("solve.pvd");
  for (const auto& [name, text] : now)
    if (name != "solve.pvd") CHECK(pvd.find("file=\"" + name + "\"") != std::string::npos);
  CHECK(temporaries(series).empty());
  // A series in a new directory that fails leaves no directory behind.
  CHECK(run_limited(1, "solve " + source("meshes/cube.obj") + " --rays 500 --solver jacobi --progressive " +
                           (dir / "fresh").string()).exit_code == 2);
  CHECK_FALSE(fs::exists(dir / "fresh"));
  fs::remove_all(dir);
}

TEST_CASE("progressive series: an empty directory name is refused in one line", "[cli]") {
  const fs::path dir = scratch() / "progressive_empty";
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const std::string& command :
       {"solve " + source("meshes/cube.obj") + " --solver jacobi --progressive ''",
        "solve " + source("meshes/cube.obj") + " --solver random-walk --walks-per-patch 8 --progressive ''",
        "pathtrace " + source("meshes/cube.obj") + " --spp 4 --progressive ''"}) {
    const Run r = run_shell("cd " + dir.string() + " && exec " + std::string(RADWALK_BINARY) + " --quiet " + command);
    INFO(command << "\n" << r.out);
    CHECK(r.exit_code == 2);
    CHECK(lines_of(r.out) == 1);
    CHECK(r.out.find("--progressive") != std::string::npos);
    CHECK(fs::is_empty(dir));  // nothing written into the current directory
  }
  fs::remove_all(dir);
}

TEST_CASE("output names of up to 255 bytes are written, paths beyond PATH_MAX or NAME_MAX are refused in one line",
          "[cli][limits]") {
  const fs::path dir = scratch() / "path_lengths";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string cube = source("meshes/cube.obj");
  // Names of 231 to 255 bytes: their temporaries must fit NAME_MAX too.
  for (const std::size_t length : {231, 250, 255}) {
    const fs::path vtp = dir / (std::string(length - 4, 'v') + ".vtp"), csv = dir / (std::string(length - 4, 'c') + ".csv");
    const Run r = run("patch " + cube + " -o " + vtp.string() + " --csv " + csv.string());
    INFO(length << "\n" << r.out);
    CHECK(r.exit_code == 0);
    CHECK(fs::file_size(vtp) > 0);
    CHECK(fs::file_size(csv) > 0);
    CHECK(temporaries(dir).empty());
  }
  // Too long: a path of more than PATH_MAX - 1 bytes ("./" repeated), a component of more than NAME_MAX bytes.
  std::string deep = source("meshes");
  while (deep.size() < 4200) deep += "/.";
  const std::string long_scene = deep + "/cube.obj", long_name = (dir / (std::string(300, 'n') + ".obj")).string();
  const std::string long_output = (dir / (std::string(300, 'o') + ".vtp")).string();
  std::string long_dir = dir.string();
  while (long_dir.size() < 4200) long_dir += "/.";
  const std::vector<std::string> commands = {
      "check " + long_scene,
      "solve " + long_scene + " --csv " + (dir / "x.csv").string(),
      "check " + long_name,
      "patch " + cube + " -o " + long_output,
      "patch " + cube + " -o " + long_dir + "/x.vtp",
      "solve " + cube + " --json " + long_dir + "/x.json",
      "solve " + cube + " --form-factors " + deep + "/cube.mtx",
      "solve " + cube + " --solver jacobi --progressive " + long_dir + "/series",
      "solve " + cube + " -o " + (dir / "x.vtp").string() + " --paraview-state " + long_dir + "/x.py"};
  for (const std::string& command : commands) {
    const Run r = run(command);
    INFO(command.substr(0, 120) << "\n" << r.out.substr(0, 400));
    CHECK(r.exit_code == 2);
    CHECK(lines_of(r.out) == 1);
    CHECK(r.out.find("path too long") != std::string::npos);
  }
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 6);  // the six written above
  fs::remove_all(dir);
}
