// End-to-end reliability checks of the radwalk program (issue 12, docs/reliability.md): the run id in every
// output, memory bounds refused or kept up front (O4), and real processes killed while writing an output (P2).
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <map>
#include <set>
#include <thread>

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
  const auto peak_kib = [](const std::string& args) {
    const std::string cmd = std::string(RADWALK_BINARY) + " -q " + args + " > /dev/null 2>&1";
    const pid_t pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
      execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    int status = 0;
    struct rusage usage {};
    REQUIRE(wait4(pid, &status, 0, &usage) == pid);
    REQUIRE(WIFEXITED(status));
    REQUIRE(WEXITSTATUS(status) == 0);
    return static_cast<double>(usage.ru_maxrss);
  };
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
      if (t.find(csv.filename().string()) != std::string::npos) seen = true;
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
