// radwalk over MPI (issue 17; README, "Running on several processes (MPI)"; docs/scaling.md, "Over MPI"): with
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
  // MPMD: rank 0 runs a good command and waits in the first collective for rank 1, whose scene is missing. Rank 1
  // waits Session::kErrorWaitSeconds (10 s) for the others to end too, then says why and aborts the job.
  const std::string good = "solve " + kScene + "--rays 200 --solver random-walk --walk shoot --particles 20000 -q";
  const std::string cmd = "timeout 120 " + mpirun(1) + " " + good + " : -np 1 " + RADWALK_BINARY + " solve " +
                          source("meshes/no_such_scene.obj") + " -q";
  const Run r = shell(cmd);
  INFO(cmd << "\n" << r.out);
  CHECK(r.exit_code == 2);  // not 124 (timeout's: a hang)
  CHECK(r.out.find("rank 1: radwalk: error: ") != std::string::npos);
  CHECK(r.out.find("no_such_scene.obj: no such file") != std::string::npos);
}
