// End-to-end checks of numbers (docs/reliability.md): one number rule for option values and text inputs, and
// outputs that stay finite or are refused in one line when a result does not fit a double.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <tuple>
#include <fstream>
#include <sstream>
#include <vector>

#include "radwalk_runner.h"

namespace fs = std::filesystem;

namespace {

// A scratch folder removed with everything in it when the case ends.
struct Scratch {
  fs::path dir;
  explicit Scratch(const std::string& name) : dir(scratch_dir("cli_numbers") / name) {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(dir.parent_path(), ec);
  }
  std::string file(const std::string& name, const std::string& text) const {
    const fs::path p = dir / name;
    std::ofstream(p) << text;
    return p.string();
  }
};

}  // namespace

TEST_CASE("one number rule: --set, --rho-scale, a response CSV and a Matrix Market value agree on every string",
          "[cli][numbers]") {
  // Every string is written where the value 0.5 (or another value in [0, 1)) would be legal on every path, so the
  // verdict depends on the number rule alone (mesh/text_scan.h parse_number: decimal only, no hex floats, no
  // blanks, no nan or inf; underflow rounds to 0, overflow is out of range).
  struct Case {
    std::string text;
    bool number;
  };
  const std::vector<Case> table = {
      {"0.5", true},     {"+0.5", true},    {".5", true},       {"5e-1", true},    {"5E-1", true},
      {"1e-400", true},  {"1e-310", true},  {"0", true},        {"-0", true},      {"0x1p-1", false},
      {"0X1P-1", false}, {"0x0", false},    {"1e400", false},   {"nan", false},    {"NaN", false},
      {"inf", false},    {"infinity", false}, {" 0.5", false},  {"0.5 ", false},   {"0.5x", false},
      {"+-0.5", false},  {"0_5", false},    {"", false},        {"0.5e", false},   {"1e+400", false},
  };
  const Scratch s("rule");
  const std::string scene = source("meshes/parallel_squares.obj");
  const auto quoted = [](const std::string& t) { return "'" + t + "'"; };
  for (const Case& c : table) {
    const Run set = run("check " + scene + " --set " + quoted("white.Kd=" + c.text));
    const Run scale = run("check " + scene + " --rho-scale " + quoted(c.text));
    const std::string csv = s.file("w.csv", "patch,w\n0," + c.text + "\n1,1\n");
    const Run response = run("measure " + scene + " --rays 16 --method direct --response csv:" + csv + ":w");
    const std::string mtx = s.file("F.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 1\n2 1 " + c.text + "\n");
    const Run matrix = run("solve " + scene + " --solver direct --form-factors " + mtx);
    INFO("'" << c.text << "'\n--set: " << set.out << "--rho-scale: " << scale.out << "csv: " << response.out
             << "mtx: " << matrix.out);
    const int expected = c.number ? 0 : 2;
    CHECK(set.exit_code == expected);
    CHECK(scale.exit_code == expected);
    CHECK(response.exit_code == expected);
    // Matrix Market separates its fields by blanks, so a blank around the value is a separator there.
    const bool blank_edge = !c.text.empty() && (c.text.front() == ' ' || c.text.back() == ' ');
    if (!blank_edge) CHECK(matrix.exit_code == expected);
    for (const Run* r : {&set, &scale, &response, &matrix})
      if (r->exit_code == 2) CHECK(std::count(r->out.begin(), r->out.end(), '\n') == 1);
  }
}

TEST_CASE("measure: an M that overflows a double is refused in one line by every method, never printed as inf",
          "[cli][numbers][measure]") {
  // parallel_squares: patch 0 (area 1) emits B_0 = pi; with R_0 = 1e308, M_0 = pi 1e308 does not fit a double,
  // whatever the method computes it from (B, the adjoint Y, walks).
  const Scratch s("overflow");
  const std::string csv = s.file("w.csv", "patch,w\n0,1e308\n1,1\n");
  const std::string scene = source("meshes/parallel_squares.obj") + " --rays 64 --response csv:" + csv + ":w";
  for (const std::string method : {"direct", "adjoint-direct", "gather-collision", "shoot-absorption",
                                   "importance-gather", "importance-shoot"}) {
    const bool deterministic = method == "direct" || method == "adjoint-direct";  // --walks does not apply
    const Run r = run("measure " + scene + (deterministic ? "" : " --walks 1000") + " --method " + method);
    INFO(method << ": " << r.out);
    CHECK(r.exit_code == 3);
    CHECK(r.out.find("inf") == std::string::npos);
    CHECK(r.out.find("nan") == std::string::npos);
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
  }
  // The largest weights that fit still give a finite M (pi 1e300 + ...).
  const std::string fits = s.file("fits.csv", "patch,w\n0,1e300\n1,1\n");
  const Run ok = run("measure " + source("meshes/parallel_squares.obj") + " --rays 64 --method direct --response csv:" +
                     fits + ":w");
  INFO(ok.out);
  CHECK(ok.exit_code == 0);
  CHECK(ok.out.find("3.14159265e+300") != std::string::npos);
}

TEST_CASE("measure --response csv: a patch listed twice, a column named twice and ragged rows exit 2 naming the line",
          "[cli][numbers][measure]") {
  const Scratch s("csv");
  const std::string scene = source("meshes/parallel_squares.obj") + " --rays 16 --method direct";
  const auto refused = [&](const std::string& text, const std::string& message) {
    const std::string csv = s.file("r.csv", text);
    const Run r = run("measure " + scene + " --response csv:" + csv + ":w");
    INFO(r.out);
    CHECK(r.exit_code == 2);
    CHECK(r.out.find(csv + ":" + message) != std::string::npos);
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
  };
  refused("patch,w\n0,1\n0,2\n", "3: --response csv:");
  refused("patch,w\n0,1\n0,2\n", "3: --response csv:" + (s.dir / "r.csv").string() + ":w: patch 0 is listed twice");
  refused("patch,w,w\n0,1,2\n", "1: --response csv:" + (s.dir / "r.csv").string() + ":w: column 'w' is named twice");
  refused("patch,w\n0,1,7\n", "2: --response csv:" + (s.dir / "r.csv").string() + ":w: the row has 3 cells");
  refused("patch,w,x\n0,1\n", "2: --response csv:" + (s.dir / "r.csv").string() + ":w: the row has 2 cells");
}

TEST_CASE("O4: path-tracer memory does not grow with the samples per patch", "[cli][limits]") {
  // The per-block sums of every patch were all held at once: 48 bytes per 256 samples of every patch, so the
  // documented maximum --spp 2^32 needed 0.19 bytes per sample. Two facing unit squares, 2^25 samples each: the
  // peak memory of the process may exceed that of a run with 256 samples by the fixed buffers of a large run (a
  // wave of 2^15 items' sums, 1.5 MB, and the samples of one task per thread, 2 x 1.5 MB) and 0.02 bytes per
  // sample, 7.3 MB in all (the old per-block sums alone were 12.6 MB here).
  const Scratch s("spp");
  const std::string csv = (s.dir / "t.csv").string();
  const long spp = 1L << 25;
  const std::string scene = source("meshes/parallel_squares.obj") + " --threads 2 --integrator nee ";
  const double small = peak_kib("pathtrace " + scene + "--spp 256");
  const double large = peak_kib("pathtrace " + scene + "--spp " + std::to_string(spp) + " --csv " + csv);
  const double samples = 2.0 * static_cast<double>(spp);
  INFO("peak " << small << " KiB with 256 samples per patch, " << large << " KiB with " << spp);
  CHECK((large - small) * 1024 < 6e6 + 0.02 * samples);
  std::ifstream in(csv);
  std::string header, row;
  REQUIRE(std::getline(in, header));
  REQUIRE(std::getline(in, row));
  CHECK(header.find("B_r") != std::string::npos);
}

namespace {

// A CSV as a table of cells (header first).
std::vector<std::vector<std::string>> csv_cells(const fs::path& path) {
  std::vector<std::vector<std::string>> table;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    table.push_back(cells);
  }
  return table;
}

std::string text_of(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The values of column `name` of a CSV (as doubles).
std::vector<double> column(const fs::path& csv, const std::string& name) {
  const auto table = csv_cells(csv);
  REQUIRE(!table.empty());
  const auto it = std::find(table[0].begin(), table[0].end(), name);
  REQUIRE(it != table[0].end());
  const auto k = static_cast<std::size_t>(it - table[0].begin());
  std::vector<double> values;
  for (std::size_t r = 1; r < table.size(); ++r) values.push_back(std::stod(table[r].at(k)));
  return values;
}

// Occurrences of `word` in `text` as a word of its own (not inside "kappa_inf" or "infinite").
std::size_t words(const std::string& text, const std::string& word) {
  std::size_t n = 0;
  const auto letter = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1))
    n += (at == 0 || !letter(text[at - 1])) && (at + word.size() >= text.size() || !letter(text[at + word.size()]));
  return n;
}

// Every number cell of the CSV filled and finite; no more nulls in the JSON than `reference` (the same command at
// Ke = 1: nulls by design, e.g. the residual of a Monte Carlo method); no nan or inf on stdout.
void check_all_finite(const Run& r, const fs::path& csv, const fs::path& json, const fs::path& reference,
                      const std::string& what) {
  INFO(what << "\n" << r.out);
  CHECK(words(r.out, "nan") + words(r.out, "inf") + words(r.out, "-nan") == 0);
  const auto table = csv_cells(csv);
  REQUIRE(table.size() > 1);
  for (std::size_t row = 1; row < table.size(); ++row) {
    CHECK(table[row].size() == table[0].size());
    for (std::size_t k = 0; k < table[row].size(); ++k) {
      INFO("row " << row << ", column " << table[0][k]);
      // The name columns may be empty (a scene without o/g statements); every number column is filled.
      const bool name = table[0][k] == "object" || table[0][k] == "group" || table[0][k] == "material";
      CHECK((name || !table[row][k].empty()));
      // run_id is a hex identifier, not a number (one of only digits and 'e' looks like one).
      if (table[0][k] != "run_id" && !table[row][k].empty() &&
          table[row][k].find_first_not_of("0123456789.e+-") == std::string::npos)
        CHECK(std::isfinite(std::stod(table[row][k])));
    }
  }
  const std::string j = text_of(json);
  INFO(j);
  CHECK(words(j, "null") == words(text_of(reference), "null"));
}

}  // namespace

TEST_CASE("huge but legal emission: every output finite and B proportional to Ke, or a one-line refusal",
          "[cli][numbers][emission]") {
  // Ke = 2^508 (E = pi Ke = 2.6e153): B, its error bars and the per-walk variances (about E^2 = 7e306) fit a
  // double, but sums of squares over 1000 samples do not: every output must be finite, and B / 2^508 must be
  // B(Ke = 1) (bit for bit in the estimators: a power of two scales exactly; to the CSV's 12 digits here).
  // Ke = 1e300: B and its error bars fit, a per-walk variance (1e600) cannot: the deterministic solvers give
  // finite outputs, B / 1e300 = B(Ke = 1) to rounding; the Monte Carlo commands refuse in one line (exit 3),
  // writing nothing.
  const Scratch s("emission");
  const std::string scene = source("meshes/parallel_squares.obj") + " ";
  const double big = std::ldexp(1.0, 508);
  char big_text[40];
  std::snprintf(big_text, sizeof big_text, "%.17g", big);
  struct Command {
    std::string name, args;
    bool monte_carlo;
  };
  const std::vector<Command> commands = {
      {"direct", "solve --solver direct --rays 1000", false},
      {"jacobi", "solve --solver jacobi --rays 1000", false},
      {"gauss-seidel", "solve --solver gauss-seidel --rays 1000", false},
      {"southwell", "solve --solver southwell --rays 1000", false},
      {"gather", "solve --rays 1000 --solver random-walk --walk gather --walks-per-patch 2000", true},
      {"shoot", "solve --rays 1000 --solver random-walk --walk shoot --particles 4000", true},
      {"gather-ray", "solve --solver random-walk --walk gather --kernel ray --walks-per-patch 2000", true},
      {"pathtrace", "pathtrace --spp 2000", true},
      {"pathtrace-light", "pathtrace --spp 2000 --integrator light", true},
  };
  const auto run_with = [&](const Command& c, const std::string& ke, const std::string& tag) {
    const fs::path csv = s.dir / (c.name + tag + ".csv"), json = s.dir / (c.name + tag + ".json");
    const Run r = run(c.args + " " + scene + "--set light.Ke=" + ke + " --csv " + csv.string() + " --json " +
                      json.string());
    return std::tuple{r, csv, json};
  };
  for (const Command& c : commands) {
    const auto [one, one_csv, one_json] = run_with(c, "1", "_1");
    REQUIRE(one.exit_code == 0);
    // Ke = 2^508: finite, B proportional.
    {
      const auto [r, csv, json] = run_with(c, big_text, "_big");
      INFO(c.name << " Ke = 2^508: " << r.out);
      REQUIRE(r.exit_code == 0);
      check_all_finite(r, csv, json, one_json, c.name + " Ke = 2^508");
      const std::vector<double> B = column(csv, "B_r"), B1 = column(one_csv, "B_r");
      REQUIRE(B.size() == B1.size());
      for (std::size_t i = 0; i < B.size(); ++i) CHECK(std::abs(B[i] / big - B1[i]) <= 1e-11 * std::abs(B1[i]));
    }
    // Ke = 1e300.
    {
      const auto [r, csv, json] = run_with(c, "1e300", "_1e300");
      INFO(c.name << " Ke = 1e300: " << r.out);
      if (!c.monte_carlo) {
        REQUIRE(r.exit_code == 0);
        check_all_finite(r, csv, json, one_json, c.name + " Ke = 1e300");
        const std::vector<double> B = column(csv, "B_r"), B1 = column(one_csv, "B_r");
        for (std::size_t i = 0; i < B.size(); ++i) CHECK(std::abs(B[i] / 1e300 - B1[i]) <= 1e-11 * std::abs(B1[i]));
      } else {
        CHECK(r.exit_code == 3);
        CHECK(r.out.find("overflows a double") != std::string::npos);
        CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
        CHECK_FALSE(fs::exists(csv));
        CHECK_FALSE(fs::exists(json));
      }
    }
  }
}

TEST_CASE("huge but legal emission: compare and measure give finite outputs or one-line refusals",
          "[cli][numbers][emission]") {
  const Scratch s("emission_compare");
  const std::string scene = source("meshes/parallel_squares.obj") + " --rays 1000 ";
  const double big = std::ldexp(1.0, 508);
  char big_text[40];
  std::snprintf(big_text, sizeof big_text, "%.17g", big);
  const std::string compare = "compare " + scene + "--estimators gather-collision,shoot-absorption --walks-per-patch 2000 --runs 3 ";
  {
    const fs::path csv = s.dir / "c.csv", json = s.dir / "c.json";
    const Run r = run(compare + "--set light.Ke=" + big_text + " --csv " + csv.string() + " --json " + json.string());
    REQUIRE(r.exit_code == 0);
    // var_theory is not computed without --theory and a zero-variance row (the emitter) has an infinite
    // efficiency (empty by design): every other cell holds a finite number.
    const std::vector<double> var = column(csv, "var");
    const auto table = csv_cells(csv);
    for (const std::string name : {"mean", "var", "var_se", "z", "efficiency"}) {
      const auto k = static_cast<std::size_t>(std::find(table[0].begin(), table[0].end(), name) - table[0].begin());
      REQUIRE(k < table[0].size());
      for (std::size_t row = 1; row < table.size(); ++row) {
        if (name == "efficiency" && var[row - 1] == 0) continue;
        INFO(name << ", row " << row << "\n" << r.out);
        REQUIRE(!table[row][k].empty());
        CHECK(std::isfinite(std::stod(table[row][k])));
      }
    }
    CHECK(words(r.out, "nan") + words(r.out, "inf") == 0);
    const Run refused = run(compare + "--set light.Ke=1e300 --csv " + (s.dir / "c2.csv").string());
    INFO(refused.out);
    CHECK(refused.exit_code == 3);
    CHECK(std::count(refused.out.begin(), refused.out.end(), '\n') == 1);
    CHECK_FALSE(fs::exists(s.dir / "c2.csv"));
  }
  for (const std::string method : {"direct", "adjoint-direct", "gather-collision", "shoot-absorption",
                                   "importance-gather"}) {
    const bool deterministic = std::string(method) == "direct" || std::string(method) == "adjoint-direct";
    const std::string measure =
        "measure " + scene + "--response patches:1" + (deterministic ? "" : " --walks 2000") + " --method " + method;
    const Run one = run(measure + " --set light.Ke=1");
    const Run r = run(measure + " --set light.Ke=" + big_text);
    INFO(method << "\n" << one.out << r.out);
    REQUIRE(one.exit_code == 0);
    REQUIRE(r.exit_code == 0);
    CHECK(words(r.out, "nan") + words(r.out, "inf") == 0);
    const Run huge = run(measure + " --set light.Ke=1e300");
    INFO(huge.out);
    if (method == "direct" || method == "adjoint-direct") {
      CHECK(huge.exit_code == 0);
      CHECK(words(huge.out, "nan") + words(huge.out, "inf") == 0);
    } else if (method == "importance-gather") {  // zero variance up to rounding: either is right
      CHECK((huge.exit_code == 0 || huge.exit_code == 3));
      CHECK(words(huge.out, "nan") + words(huge.out, "inf") == 0);
    } else {
      CHECK(huge.exit_code == 3);
      CHECK(std::count(huge.out.begin(), huge.out.end(), '\n') == 1);
    }
  }
}
