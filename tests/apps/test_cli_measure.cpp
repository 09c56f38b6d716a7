// End-to-end: `radwalk measure`: every method gives the same M within its error bar, the deterministic ones agree
// to rounding, the exact importance gives zero variance, responses by patch, material, group and CSV, and one-line
// refusals of bad responses and methods.
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "radwalk_runner.h"
#include "support/statistics.h"

namespace {

struct Measured {
  double M[3], se[3];
  double walks_se[3];  // the walks' own part of se (the form factors' noise excluded): for methods on one F
};

Measured measured(const std::string& args) {
  const std::filesystem::path json = scratch_dir("cli_measure") / "m.json";
  const Run r = run("measure " + args + " --json " + json.string());
  INFO("radwalk measure " << args << " -> " << r.out);
  REQUIRE(r.exit_code == 0);
  std::ifstream in(json);
  const nlohmann::json j = nlohmann::json::parse(in);
  Measured m{};
  for (int c = 0; c < 3; ++c) {
    m.M[c] = j["measurement"]["M"][c].get<double>();
    m.se[c] = j["measurement"].contains("M_se") ? j["measurement"]["M_se"][c].get<double>() : 0.0;
    const auto& stat = j["error_estimate"]["statistical"];
    m.walks_se[c] = stat.contains("walks_M_se") ? stat["walks_M_se"][c].get<double>() : m.se[c];
  }
  return m;
}

}  // namespace

TEST_CASE("radwalk measure: every method estimates the same M", "[cli][measure][statistical]") {
  const std::string scene = source("meshes/cornell_box.obj") + " --rays 500 --seed 3 --response material:white";
  const Measured direct = measured(scene + " --method direct");
  const Measured adjoint = measured(scene + " --method adjoint-direct");
  for (int c = 0; c < 3; ++c) CHECK(adjoint.M[c] == Approx(direct.M[c]).epsilon(1e-9));  // rounding of two LU solves
  // The walk methods: z-tests against the direct M of the same F (so with the walks' own standard error, not the
  // form factors' noise they share), 8 methods x 3 channels at family-wise alpha = 1e-3.
  const double z_crit = radwalk::z_critical(radwalk::sidak(1e-3, 8 * 3));
  for (const std::string method : {"gather-collision", "gather-absorption", "gather-expected-value", "shoot-collision",
                                   "shoot-absorption", "shoot-survival", "importance-gather", "importance-shoot"}) {
    const Measured m = measured(scene + " --walks 20000 --method " + method +
                                (method.rfind("importance", 0) == 0 ? " --importance-sweeps 2" : ""));
    for (int c = 0; c < 3; ++c) {
      INFO(method << " channel " << c << ": " << m.M[c] << " +- " << m.walks_se[c] << " vs " << direct.M[c]);
      CHECK(std::abs(m.M[c] - direct.M[c]) <= z_crit * m.walks_se[c]);
      CHECK(m.se[c] > m.walks_se[c]);  // the total includes the form factors' noise
    }
  }
  // The exact importance: every walk scores M (zero variance up to rounding).
  const Measured exact = measured(scene + " --walks 1000 --method importance-shoot");
  for (int c = 0; c < 3; ++c) {
    CHECK(exact.M[c] == Approx(direct.M[c]).epsilon(1e-12));
    CHECK(exact.walks_se[c] < 1e-10 * direct.M[c]);
    // The deterministic methods' standard error is the form factors' noise alone, the same for both.
    CHECK(direct.se[c] > 0);
    CHECK(adjoint.se[c] == Approx(direct.se[c]).epsilon(1e-6));
  }
}

TEST_CASE("radwalk measure: responses by patch, group and CSV column", "[cli][measure]") {
  const std::string cube = source("meshes/cube.obj") + " --rays 200 --method direct";
  const Measured one = measured(cube + " --response patches:0");
  const Measured two = measured(cube + " --response patches:0,1");
  // A CSV with weight 1 on patches 0 and 1 measures what patches:0,1 does.
  const std::filesystem::path csv = scratch_dir("cli_measure") / "w.csv";
  std::ofstream(csv) << "patch,w\n0,1\n1,1\n";
  const Measured from_csv = measured(cube + " --response csv:" + csv.string() + ":w");
  // The cube with its floor and ceiling in OBJ group 'caps': group:caps measures what patches:0,1 does.
  const std::filesystem::path dir = scratch_dir("cli_measure");
  std::filesystem::copy_file(source("meshes/cube.mtl"), dir / "cube.mtl",
                             std::filesystem::copy_options::overwrite_existing);
  {
    std::ifstream in(source("meshes/cube.obj"));
    std::ofstream out(dir / "grouped.obj");
    std::string line;
    int faces = 0;
    while (std::getline(in, line)) {
      if (line.rfind("f ", 0) == 0) out << (faces++ < 2 ? "g caps\n" : "g walls\n");
      out << line << "\n";
    }
  }
  const Measured grouped =
      measured((dir / "grouped.obj").string() + " --rays 200 --method direct --response group:caps");
  for (int c = 0; c < 3; ++c) {
    CHECK(two.M[c] > one.M[c]);
    CHECK(from_csv.M[c] == two.M[c]);
    CHECK(grouped.M[c] == two.M[c]);
  }
}

TEST_CASE("radwalk measure: a camera response by the direct and the adjoint solve", "[cli][measure]") {
  const std::string box = source("meshes/cornell_box.obj") + " --rays 300 --response camera --width 64 --height 64";
  const Measured direct = measured(box + " --method direct");
  const Measured adjoint = measured(box + " --method adjoint-direct");
  for (int c = 0; c < 3; ++c) {
    CHECK(direct.M[c] > 0);
    CHECK(adjoint.M[c] == Approx(direct.M[c]).epsilon(1e-9));
  }
}

TEST_CASE("radwalk measure: bad responses and methods are one-line refusals", "[cli][measure]") {
  const std::string box = source("meshes/cornell_box.obj") + " --rays 100";
  const auto refused = [](const std::string& args, const std::string& words) {
    const Run r = run("measure " + args);
    INFO("radwalk measure " << args << " -> " << r.out);
    CHECK(r.exit_code == 2);
    CHECK(r.out.find(words) != std::string::npos);
  };
  refused(box + " --response material:whte", "did you mean 'white'");
  refused(box + " --response patches:99999", "is not a patch");
  refused(box + " --response group:nothing", "no OBJ object or group 'nothing'");
  refused(box + " --response sensor:1", "unknown kind 'sensor'");
  refused(box + " --response patches:0 --method adjoint-drect", "did you mean 'adjoint-direct'");
}
