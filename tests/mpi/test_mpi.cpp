// radwalk over MPI (docs/mpi.md; docs/scaling.md, "Over MPI"): with
// 1, 2 and 3 ranks (mpirun --oversubscribe: more ranks than this machine's cores) every output of the distributed
// stages is the same byte for byte as one process's (form factors, random walks on both kernels, path-traced patch
// averages and images, Jacobi), except the documented fields that record how a run went (the .vtp's timing
// entries, as in tests/apps/test_determinism.cpp); Gauss-Seidel, which becomes block Gauss-Seidel over ranks,
// agrees within the error its tolerance allows; bad input is one line and exit 2 from the whole job, also when
// only one rank fails.
// mpirun refuses to start as root unless told: OMPI_ALLOW_RUN_AS_ROOT(_CONFIRM)=1 are set here for that case.
#include <cstdlib>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/radwalk_runner.h"
#include "apps/run_id_reader.h"

namespace fs = std::filesystem;

namespace {

// The output of a shell command line (stdout and stderr merged) and its exit code.
Run shell(const std::string& cmd) {
  Run r{-1, {}};
  FILE* pipe = popen((cmd + " 2>&1").c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), buf.size(), pipe)) r.out += buf.data();
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// "mpirun -np R ... radwalk": quiet (-q: no launcher banners), more ranks than cores allowed, ranks not pinned;
// root allowed (CI containers run as root).
std::string mpirun(int ranks) {
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
  return std::string(RADWALK_MPIRUN) + " -q --oversubscribe --bind-to none -np " + std::to_string(ranks) + " " +
         RADWALK_BINARY;
}

// The bytes compared: a .vtp without the entries that record how the run went (timings, the command line).
std::string comparable(const fs::path& path) {
  const std::string text = file_text(path);
  if (path.extension() == ".vtp") {
    static const std::regex run_dependent(
        R"re(<(Array|DataArray) [^>]*Name="(command_line|[A-Za-z_]*seconds[A-Za-z_]*)"[^>]*>[^<]*</\1>\s*)re");
    return std::regex_replace(text, run_dependent, "");
  }
  return text;
}

// Runs `args` (naming outputs OUT/...) in one process, then with 1, 2 and 3 ranks (one thread each), and
// compares every file written (also in subdirectories) with the single process's.
void same_as_one_process(const std::string& name, const std::string& args, std::size_t expected_files) {
  const fs::path root = scratch_dir("mpi") / name;
  fs::remove_all(root);
  auto run_in = [&](const std::string& launcher, const std::string& tag) {
    const fs::path dir = root / tag;
    fs::create_directories(dir);
    const std::string cmd = launcher + " --quiet " +
                            std::regex_replace(args, std::regex("OUT/"), dir.string() + "/") + " --threads 1";
    const Run r = shell(cmd);
    INFO(cmd << "\n" << r.out);
    REQUIRE(r.exit_code == 0);
    std::map<std::string, std::string> files;
    for (const auto& e : fs::recursive_directory_iterator(dir))
      if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = comparable(e.path());
    return files;
  };
  const auto reference = run_in(RADWALK_BINARY, "one");
  if (expected_files > 0) REQUIRE(reference.size() == expected_files);  // 0: a series of unknown length
  for (int ranks = 1; ranks <= 3; ++ranks) {
    const auto files = run_in(mpirun(ranks), "ranks" + std::to_string(ranks));
    REQUIRE(files.size() == reference.size());  // rank 0 wrote them all, the others nothing beside them
    for (const auto& [file, bytes] : reference) {
      INFO(name << ", " << ranks << " ranks: " << file);
      REQUIRE(files.count(file));
      const std::string& other = files.at(file);
      if (bytes == other) continue;
      std::size_t at = 0;
      while (at < bytes.size() && at < other.size() && bytes[at] == other[at]) ++at;
      const std::size_t from = at > 100 ? at - 100 : 0;
      FAIL_CHECK("differ at byte " << at << ":\none process: " << bytes.substr(from, 200) << "\n" << ranks
                                   << " ranks: " << other.substr(from, 200));
    }
  }
}

const std::string kScene = source("meshes/cornell_box.obj") + " --max-edge 100 --seed 5 ";
const std::string kOutputs = "-o OUT/B.vtp --csv OUT/B.csv";

// Per-patch columns of a CSV by name.
std::map<std::string, std::vector<double>> csv_columns(const fs::path& path) {
  std::stringstream in(file_text(path));
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::stringstream header(line);
  for (std::string c; std::getline(header, c, ',');) names.push_back(c);
  std::map<std::string, std::vector<double>> columns;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::string cell;
    for (std::size_t k = 0; k < names.size() && std::getline(row, cell, ','); ++k)
      columns[names[k]].push_back(cell.empty() ? 0.0 : std::strtod(cell.c_str(), nullptr));
  }
  return columns;
}

// Block Gauss-Seidel over R ranks and Gauss-Seidel on one process each stop at a relative residual
// rho = max_ic |r_ic| / max_i E_ic <= tol. With A = I - diag(rho_c) F, B - B* = A^-1 r, so per channel
// |B - B*| <= ||A^-1||_inf rho max E_c <= kappa_inf rho max E_c (||A||_inf >= 1: a unit diagonal, F_ii = 0 on
// planar patches), and two such solves differ by at most kappa (rho_1 + rho_R) max E_c, plus the CSV's rounding
// to 12 significant digits (5e-12 relative, each side). kappa_inf is the direct solve's (exact, direct_solver.h).
// `base`: the scene and form-factor arguments of `radwalk solve`.
void gauss_seidel_agrees(const std::string& name, const std::string& base) {
  const fs::path dir = scratch_dir("mpi") / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  const Run direct = shell(std::string(RADWALK_BINARY) + " solve " + base + "--solver direct --json " +
                           (dir / "direct.json").string());
  REQUIRE(direct.exit_code == 0);
  const double kappa =
      nlohmann::json::parse(file_text(dir / "direct.json"))["solution"]["info"]["condition_estimate"].get<double>();
  REQUIRE(kappa >= 1);
  auto solve = [&](const std::string& launcher, const std::string& tag) {
    const std::string cmd = launcher + " solve " + base + "--solver gauss-seidel --tol 1e-8 --csv " +
                            (dir / (tag + ".csv")).string() + " --json " + (dir / (tag + ".json")).string();
    const Run r = shell(cmd);
    INFO(cmd << "\n" << r.out);
    REQUIRE(r.exit_code == 0);
    const nlohmann::json j = nlohmann::json::parse(file_text(dir / (tag + ".json")));
    CHECK(j["solution"]["status"] == "converged");
    return std::pair{csv_columns(dir / (tag + ".csv")), j["solution"]["residual"].get<double>()};
  };
  const auto [one, residual_one] = solve(RADWALK_BINARY, "one");
  CHECK(residual_one <= 1e-8);
  for (int ranks = 2; ranks <= 3; ++ranks) {
    const auto [many, residual_many] = solve(mpirun(ranks), "ranks" + std::to_string(ranks));
    CHECK(residual_many <= 1e-8);
    for (const char* c : {"r", "g", "b"}) {
      const std::vector<double>& B1 = one.at(std::string("B_") + c);
      const std::vector<double>& BR = many.at(std::string("B_") + c);
      const std::vector<double>& E = one.at(std::string("E_") + c);
      REQUIRE(B1.size() == BR.size());
      double max_E = 0;
      for (double e : E) max_E = std::max(max_E, std::abs(e));
      for (std::size_t i = 0; i < B1.size(); ++i) {
        const double bound = kappa * (residual_one + residual_many) * max_E + 5e-12 * (std::abs(B1[i]) + std::abs(BR[i]));
        INFO(name << ", " << ranks << " ranks, patch " << i << ", channel " << c << ": " << B1[i] << " vs " << BR[i]
                  << ", bound " << bound);
        CHECK(std::abs(B1[i] - BR[i]) <= bound);
      }
    }
  }
}

// Runs `args` (a formfactors or solve command line without --json) with R ranks and returns its JSON summary.
nlohmann::json json_of(int ranks, const std::string& args, const fs::path& json) {
  const std::string cmd = mpirun(ranks) + " --quiet " + args + " --threads 1 --json " + json.string();
  const Run r = shell(cmd);
  INFO(cmd << "\n" << r.out);
  REQUIRE(r.exit_code == 0);
  return nlohmann::json::parse(file_text(json));
}

// The rows each rank held, from the JSON: the stored non-zeros of every rank sum to nnz(F), and with R >= 2 ranks
// none holds them all (every rank held its own rows only, and no stage gathered the whole F on every rank).
void check_rows_distributed(const nlohmann::json& j, int ranks) {
  INFO(j.dump());
  const auto total = j["form_factor_nonzeros"].get<std::uint64_t>();
  REQUIRE(total > 0);
  const auto by_rank = j["mpi"]["form_factor_nonzeros_by_rank"].get<std::vector<std::uint64_t>>();
  REQUIRE(by_rank.size() == std::size_t(ranks));
  std::uint64_t sum = 0;
  for (std::uint64_t k : by_rank) {
    sum += k;
    CHECK(k > 0);  // every block has rows with non-zeros in this closed scene
    CHECK(k < total);
  }
  CHECK(sum == total);
  CHECK(j["mpi"]["whole_form_factor_gathers"] == 0);
}

}  // namespace

TEST_CASE("over MPI the form factors are byte-identical to one process's", "[mpi]") {
  same_as_one_process("formfactors", "formfactors " + kScene + "--rays 200 -o OUT/F.mtx --csv OUT/F.csv --vtp OUT/F.vtp",
                      3);
  same_as_one_process("formfactors-density",
                      "formfactors " + source("meshes/cube.obj") + " --max-edge 0.4 --rays-per-area 4000 -o OUT/F.mtx", 1);
  // The binary file too: rank 0 gathers the other ranks' rows to write it.
  same_as_one_process("formfactors-npz", "formfactors " + kScene + "--rays 200 -o OUT/F.npz", 1);
}

TEST_CASE("over MPI random walks on the matrix kernel are byte-identical to one process's", "[mpi]") {
  same_as_one_process("gather-matrix", "solve " + kScene + "--rays 200 --solver random-walk --walks-per-patch 40 " +
                                           kOutputs, 2);
  same_as_one_process("shoot-matrix", "solve " + kScene + "--rays 200 --solver random-walk --walk shoot "
                                          "--particles 20000 " + kOutputs, 2);
  same_as_one_process("shoot-sobol-matrix", "solve " + kScene + "--rays 200 --solver random-walk --walk shoot "
                                                "--sampler sobol --direct-light --particles 20000 " + kOutputs, 2);
}

TEST_CASE("over MPI random walks on the ray kernel are byte-identical to one process's", "[mpi]") {
  same_as_one_process("gather-ray", "solve " + kScene + "--kernel ray --solver random-walk --walks-per-patch 40 " +
                                        kOutputs, 2);
  same_as_one_process("shoot-ray", "solve " + kScene + "--kernel ray --solver random-walk --walk shoot "
                                       "--estimator absorption --particles 20000 " + kOutputs, 2);
  same_as_one_process("shoot-sobol-ray", "solve " + kScene + "--kernel ray --solver random-walk --walk shoot "
                                             "--sampler sobol --direct-light --particles 20000 " + kOutputs, 2);
}

TEST_CASE("over MPI the path tracer's patch averages and images are byte-identical to one process's", "[mpi]") {
  same_as_one_process("pathtrace", "pathtrace " + kScene + "--spp 8 " + kOutputs, 2);
  same_as_one_process("render", "pathtrace " + kScene + "--spp 4 --width 32 --height 23 --image OUT/i.png", 1);
}

TEST_CASE("over MPI Jacobi is byte-identical and Gauss-Seidel agrees within its tolerance", "[mpi]") {
  same_as_one_process("jacobi", "solve " + kScene + "--rays 200 --solver jacobi " + kOutputs, 2);
  // The iterates as a ParaView series (written, thinned and renamed by rank 0 alone).
  same_as_one_process("jacobi-progressive",
                      "solve " + kScene + "--rays 200 --solver jacobi --progressive OUT/series --csv OUT/B.csv", 0);

  gauss_seidel_agrees("gauss-seidel", kScene + "--rays 200 --threads 1 --quiet ");
}

TEST_CASE("over MPI F is row-distributed: each rank holds its rows, and solves from a read file match one process",
          "[mpi]") {
  const fs::path dir = scratch_dir("mpi") / "rows";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string scene = kScene + "--rays 200 ";
  // Estimated: each rank traces and keeps its rows (blocks balanced by rays), also while rank 0 writes the file.
  for (int ranks = 2; ranks <= 3; ++ranks) {
    const std::string tag = std::to_string(ranks);
    check_rows_distributed(json_of(ranks, "formfactors " + scene + "-o " + (dir / ("F" + tag + ".npz")).string(),
                                   dir / ("formfactors" + tag + ".json")),
                           ranks);
    check_rows_distributed(json_of(ranks, "solve " + scene + "--solver jacobi --csv " + (dir / "B.csv").string(),
                                   dir / ("jacobi" + tag + ".json")),
                           ranks);
  }
  // Read: each rank copies only its block of rows (balanced by non-zeros) from the mapped .npz, or keeps only its
  // rows of the .mtx; Jacobi is then byte-identical to one process, Gauss-Seidel agrees within its tolerance.
  const fs::path npz = dir / "F.npz", mtx = dir / "F.mtx";
  for (const fs::path& f : {npz, mtx}) {
    const Run w = shell(std::string(RADWALK_BINARY) + " formfactors " + scene + "--quiet -o " + f.string());
    REQUIRE(w.exit_code == 0);
  }
  for (const fs::path& f : {npz, mtx}) {
    const std::string read = kScene + "--form-factors " + f.string() + " ";
    same_as_one_process("jacobi-read" + f.extension().string(), "solve " + read + "--solver jacobi " + kOutputs, 2);
    for (int ranks = 2; ranks <= 3; ++ranks)
      check_rows_distributed(json_of(ranks, "solve " + read + "--solver jacobi --csv " + (dir / "B.csv").string(),
                                     dir / ("read" + std::to_string(ranks) + ".json")),
                             ranks);
  }
  gauss_seidel_agrees("gauss-seidel-read", kScene + "--form-factors " + npz.string() + " --threads 1 --quiet ");
  // A stage that needs the whole F gathers it (counted): the direct solve of a small scene.
  const nlohmann::json direct = json_of(2, "solve " + kScene + "--form-factors " + npz.string() + " --solver direct",
                                        dir / "direct.json");
  CHECK(direct["mpi"]["whole_form_factor_gathers"] == 1);
}

TEST_CASE("over MPI a bad row that only its rank reads is one line and exit 2 for the whole job", "[mpi]") {
  // The last row of the .mtx made to sum above 1: only the last rank keeps (and checks) it.
  const fs::path dir = scratch_dir("mpi") / "bad-row";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path good = dir / "F.mtx", bad = dir / "bad.mtx";
  const Run w = shell(std::string(RADWALK_BINARY) + " formfactors " + kScene + "--rays 200 --quiet -o " + good.string());
  REQUIRE(w.exit_code == 0);
  std::string text = file_text(good);
  while (!text.empty() && text.back() == '\n') text.pop_back();
  const std::size_t last = text.rfind(' ');
  REQUIRE(last != std::string::npos);
  text = text.substr(0, last) + " 1\n";  // the row's other entries now push its sum above 1
  {
    std::ofstream out(bad);
    out << text;
  }
  const std::string args = "solve " + kScene + "--form-factors " + bad.string() + " --solver jacobi";
  const Run one = shell(std::string(RADWALK_BINARY) + " --quiet " + args);
  REQUIRE(one.exit_code == 2);
  REQUIRE(one.out.find("sums to") != std::string::npos);
  for (int ranks = 2; ranks <= 3; ++ranks) {
    const Run r = shell("timeout 120 " + mpirun(ranks) + " --quiet " + args);
    INFO(ranks << " ranks\n" << r.out);
    CHECK(r.exit_code == 2);
    CHECK(r.out == one.out);  // rank 0's one line, found by the last rank
  }
}

TEST_CASE("over MPI bad input on every rank is one line and exit 2 for the whole job", "[mpi]") {
  const fs::path dir = scratch_dir("mpi") / "bad-input";
  fs::create_directories(dir);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"solve " + source("meshes/no_such_scene.obj"), "no_such_scene.obj: no such file"},
      {"solve " + kScene + "--max-egde 3", "did you mean '--max-edge'"},
      {"solve " + kScene + "--rays 0", "--rays"},
      // The direct solve is not distributed: refused above the size where it costs about a second.
      {"solve " + source("meshes/cornell_box.obj") + " --max-edge 25 --rays 4 --solver direct --csv " +
           (dir / "B.csv").string(),
       "not distributed"},
  };
  for (const auto& [args, says] : cases) {
    const Run r = shell(mpirun(3) + " --quiet " + args);
    INFO(args << "\n" << r.out);
    CHECK(r.exit_code == 2);
    std::size_t errors = 0;  // lines "radwalk: error: ..."
    for (std::size_t at = r.out.find("radwalk: error: "); at != std::string::npos;
         at = r.out.find("radwalk: error: ", at + 1))
      ++errors;
    CHECK(errors == 1);
    CHECK(r.out.find(says) != std::string::npos);
    if (says == "not distributed") continue;  // one process solves it
    // The same output as one process: rank 0's one line, nothing from the others or the launcher.
    const Run one = shell(std::string(RADWALK_BINARY) + " --quiet " + args);
    CHECK(one.exit_code == 2);
    CHECK(r.out == one.out);
  }
  CHECK_FALSE(fs::exists(dir / "B.csv"));
}

TEST_CASE("over MPI an input error on one rank alone ends the job with exit 2 and no hang", "[mpi]") {
  // MPMD: both ranks run the same command, but rank 1's scene is missing (a node without its copy). The ranks
  // compare what they read once the scene is read (apps/rank_agreement.h): rank 0 names rank 1's refusal at once.
  const std::string options =
      " --max-edge 100 --seed 5 --rays 200 --solver random-walk --walk shoot --particles 20000 -q";
  const std::string missing = source("meshes/no_such_scene.obj");
  const std::string cmd = "timeout -k 10 120 " + mpirun(1) + " solve " + source("meshes/cornell_box.obj") + options +
                          " : -np 1 " + RADWALK_BINARY + " solve " + missing + options;
  const Run r = shell(cmd);
  INFO(cmd << "\n" << r.out);
  CHECK(r.exit_code == 2);  // not 124 (timeout's: a hang)
  CHECK(r.out == "radwalk: error: MPI rank 1 refuses its inputs, rank 0 does not: " + missing + ": no such file\n");
}

namespace {

// A scratch directory for one test, removed with everything in it when the test ends.
struct ScratchDir {
  fs::path path;
  explicit ScratchDir(const std::string& name) : path(scratch_dir("mpi") / name) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~ScratchDir() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
    fs::remove(path.parent_path(), ignored);  // the process's scratch folder, when no other test left files there
  }
};

// Two ranks of one job running different command lines (MPMD: mpirun ... -np 1 radwalk A : -np 1 radwalk B), each
// in its own working directory when one is given; killed after `seconds` (exit code 124: the job hung).
Run two_ranks(const std::string& rank0, const std::string& rank1, const fs::path& dir0 = {},
              const fs::path& dir1 = {}, int seconds = 60) {
  mpirun(1);  // sets the environment mpirun needs as root
  auto app = [](const fs::path& dir, const std::string& args) {
    return "-np 1 " + (dir.empty() ? std::string() : "-wdir " + dir.string() + " ") + RADWALK_BINARY + " " + args;
  };
  const std::string cmd = "timeout -k 10 " + std::to_string(seconds) + " " + RADWALK_MPIRUN +
                          " -q --oversubscribe --bind-to none " + app(dir0, rank0) + " : " + app(dir1, rank1);
  Run r = shell(cmd);
  r.out = cmd + "\n" + r.out;  // for the messages; the output itself follows the first line
  return r;
}

// What a run printed, without the command line two_ranks put first.
std::string printed(const Run& r) { return r.out.substr(r.out.find('\n') + 1); }

// The files below `dir` (what a refused job must not have written).
std::vector<std::string> files_in(const fs::path& dir) {
  std::vector<std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files.push_back(e.path().string());
  return files;
}

}  // namespace

TEST_CASE("over MPI ranks that run different commands are refused at start-up with one line and exit 2", "[mpi]") {
  const ScratchDir dir("commands");
  const std::string scene = source("meshes/cornell_box.obj") + " --max-edge 100 --seed 5 --rays 200 -q ";
  const Run r = two_ranks("solve " + scene + "--solver jacobi --csv " + (dir.path / "B.csv").string(),
                          "formfactors " + scene + "-o " + (dir.path / "F.mtx").string());
  INFO(r.out);
  CHECK(r.exit_code == 2);  // not 124: before the agreement the two commands waited in different collectives
  CHECK(printed(r) == "radwalk: error: MPI rank 1 runs 'formfactors' but rank 0 runs 'solve'\n");
  CHECK(files_in(dir.path).empty());
}

TEST_CASE("over MPI ranks with different option values are refused at start-up with one line naming the first",
          "[mpi]") {
  const ScratchDir dir("options");
  const std::string base = "solve " + source("meshes/cornell_box.obj") + " --max-edge 100 -q --csv " +
                           (dir.path / "B.csv").string() + " ";
  const std::string walks = "--solver random-walk --walk shoot --particles 20000 ";
  const std::string kSame = " (every rank must run the same command with the same options)\n";
  struct Case {
    std::string rank0, rank1, says;
  };
  const std::vector<Case> cases = {
      // Different seeds: F rows and walks of two seeds put together.
      {walks + "--seed 3", walks + "--seed 7", "MPI rank 1 has --seed 7, rank 0 has --seed 3"},
      {walks, walks + "--seed 7", "MPI rank 1 has --seed 7, rank 0 has --seed 1 (the default)"},
      // Different solvers: one rank's solver ignored.
      {"--solver jacobi", "--solver gauss-seidel", "MPI rank 1 has --solver gauss-seidel, rank 0 has --solver jacobi"},
      // Different ray counts: F rows of two budgets.
      {walks + "--rays 200", walks + "--rays 100", "MPI rank 1 has --rays 100, rank 0 has --rays 200"},
      // Different walk budgets.
      {walks + "--seed 3", "--solver random-walk --walk shoot --particles 30000 --seed 3",
       "MPI rank 1 has --particles 30000, rank 0 has --particles 20000"},
      // A flag on one rank only.
      {"--solver jacobi --two-sided", "--solver jacobi", "MPI rank 1 has no --two-sided, rank 0 has --two-sided"},
      // An output on one rank only (some writers gather from every rank).
      {"--solver jacobi --json " + (dir.path / "B.json").string(), "--solver jacobi",
       "MPI rank 1 has no --json, rank 0 has --json"},
  };
  for (const Case& c : cases) {
    const Run r = two_ranks(base + c.rank0, base + c.rank1);
    INFO(r.out);
    CHECK(r.exit_code == 2);
    CHECK(printed(r) == "radwalk: error: " + c.says + kSame);
    CHECK(files_in(dir.path).empty());
  }
}

TEST_CASE("over MPI ranks may differ in --threads and in the names of their output files", "[mpi]") {
  // Not refused: 1 and N threads compute the same, and only rank 0 writes.
  const ScratchDir dir("per-rank");
  const std::string base = "solve " + source("meshes/cornell_box.obj") + " --max-edge 100 --seed 5 --rays 200 -q "
                           "--solver random-walk --walk shoot --particles 20000 ";
  const Run r = two_ranks(base + "--threads 1 --csv " + (dir.path / "B.csv").string(),
                          base + "--threads 2 --csv " + (dir.path / "other.csv").string());
  INFO(r.out);
  CHECK(r.exit_code == 0);
  CHECK(printed(r).find("radwalk: error") == std::string::npos);
  CHECK(files_in(dir.path) == std::vector<std::string>{(dir.path / "B.csv").string()});
}

TEST_CASE("over MPI ranks that read different input bytes are refused with one line naming the file and exit 2",
          "[mpi]") {
  // Node-local copies: the same relative names in two working directories (mpirun -wdir), one copy changed.
  const ScratchDir dir("inputs");
  const fs::path out = dir.path / "out", d0 = dir.path / "rank0", d1 = dir.path / "rank1";
  for (const fs::path& d : {out, d0, d1}) fs::create_directories(d);
  const std::string scene = file_text(source("meshes/cornell_box.obj"));
  const std::string mtl = file_text(source("meshes/cornell_box.mtl"));
  auto write = [](const fs::path& path, const std::string& text) {
    std::ofstream f(path, std::ios::binary);
    f << text;
  };
  auto copies = [&](const std::string& scene1, const std::string& mtl1) {
    write(d0 / "scene.obj", scene);
    write(d0 / "cornell_box.mtl", mtl);
    write(d1 / "scene.obj", scene1);
    write(d1 / "cornell_box.mtl", mtl1);
  };
  const std::string args = "solve scene.obj --max-edge 100 --seed 5 --rays 200 -q --solver jacobi --csv " +
                           (out / "B.csv").string();
  const std::string kSame = " (every rank must read the same inputs)\n";

  // The scene with one more face on rank 1: a different patch count (before the agreement, an abort inside MPI).
  copies(scene + "v 1 1 1\nv 2 1 1\nv 1 2 1\nf -3 -2 -1\n", mtl);
  {
    const Run r = two_ranks(args, args, d0, d1);
    INFO(r.out);
    CHECK(r.exit_code == 2);
    CHECK(printed(r) == "radwalk: error: MPI ranks 0 and 1 read different bytes from scene.obj" + kSame);
    CHECK(files_in(out).empty());
  }
  // Another reflectance in rank 1's material library: the same patches, two scenes' rows put together (before
  // the agreement, a wrong B without a word).
  std::string mtl1 = mtl;
  const std::size_t kd = mtl1.find("Kd ");
  REQUIRE(kd != std::string::npos);
  mtl1.replace(kd, 3, "Kd 0.01 0.01 0.01\n#");
  copies(scene, mtl1);
  {
    const Run r = two_ranks(args, args, d0, d1);
    INFO(r.out);
    CHECK(r.exit_code == 2);
    CHECK(printed(r) == "radwalk: error: MPI ranks 0 and 1 read different bytes from cornell_box.mtl" + kSame);
    CHECK(files_in(out).empty());
  }
  // Different --form-factors files (two seeds' F) under the same name.
  copies(scene, mtl);
  for (const auto& [d, seed] : {std::pair{d0, "1"}, std::pair{d1, "2"}}) {
    const Run w = shell("cd " + d.string() + " && " + RADWALK_BINARY +
                        " formfactors scene.obj --max-edge 100 --rays 200 -q -o F.mtx --seed " + seed);
    REQUIRE(w.exit_code == 0);
  }
  {
    const std::string read = "solve scene.obj --max-edge 100 -q --solver jacobi --form-factors F.mtx --csv " +
                             (out / "B.csv").string();
    const Run r = two_ranks(read, read, d0, d1);
    INFO(r.out);
    CHECK(r.exit_code == 2);
    CHECK(printed(r) == "radwalk: error: MPI ranks 0 and 1 read different bytes from F.mtx" + kSame);
    CHECK(files_in(out).empty());
  }
  // The same bytes at different paths agree (node-local copies need not share a path).
  {
    const std::string same = " --max-edge 100 --seed 5 --rays 200 -q --solver jacobi --csv " + (out / "B.csv").string();
    const Run r =
        two_ranks("solve " + (d0 / "scene.obj").string() + same, "solve " + (d1 / "scene.obj").string() + same);
    INFO(r.out);
    CHECK(r.exit_code == 0);
    CHECK(fs::exists(out / "B.csv"));
  }
}
