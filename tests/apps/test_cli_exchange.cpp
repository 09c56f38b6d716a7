// `radwalk exchange` end to end (docs/heat-exchange.md): the unit cube in metres with six materials of different
// emissivity and temperature (one re-radiating) against an independent dense solve of the net-radiation equations
// with the cube's exact view factors; the energy balance; the group view-factor table (reciprocity, rows summing to
// 1); the traced route within its error bars against the analytic one; the refusals.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "radwalk_runner.h"
#include "support/reference_problems.h"
#include "support/statistics.h"

namespace fs = std::filesystem;

namespace {

constexpr double sigma = 5.670374419e-8;

// Faces in the order x=0, x=1, y=0, y=1, z=0, z=1 (face i opposite face i ^ 1), normals inward, each its own
// material t0..t5.
const double kEps[6] = {0.9, 0.3, 0.55, 0.7, 1.0, 0.05};
const double kT[6] = {600, 300, 350, 0, 280, 450};  // face 3 re-radiating (heat flux 0)

fs::path write_cube(const fs::path& dir, const std::string& extra_mtl = "") {
  std::ofstream mtl(dir / "thermal.mtl");
  for (int i = 0; i < 6; ++i) {
    mtl << "newmtl t" << i << "\nKd 0.5\nradwalk_emissivity " << kEps[i] << "\n";
    if (i == 3)
      mtl << "radwalk_heat_flux 0\n";
    else
      mtl << "radwalk_temperature " << kT[i] << "\n";
  }
  mtl << extra_mtl;
  std::ofstream obj(dir / "thermal.obj");
  obj << "mtllib thermal.mtl\n"
         "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
         "o x0\nusemtl t0\nf 1 4 8 5\n"   // x = 0, normal +x
         "o x1\nusemtl t1\nf 2 6 7 3\n"   // x = 1, normal -x
         "o y0\nusemtl t2\nf 1 5 6 2\n"   // y = 0, normal +y
         "o y1\nusemtl t3\nf 4 3 7 8\n"   // y = 1, normal -y
         "o z0\nusemtl t4\nf 1 2 3 4\n"   // z = 0, normal +z
         "o z1\nusemtl t5\nf 5 8 7 6\n";  // z = 1, normal -z
  return dir / "thermal.obj";
}

// The net-radiation equations in the unknowns (J, G, q, sigma T^4) with the exact F in double, full-pivoting LU.
struct Reference {
  double J[6], q[6], T[6];
};
Reference reference() {
  const int n = 6;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(4 * n, 4 * n);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(4 * n);
  for (int i = 0; i < n; ++i) {
    A(i, n + i) = 1;
    for (int j = 0; j < n; ++j)
      if (j != i) A(i, j) = -((i ^ 1) == j ? radwalk::test::kOpposite : radwalk::test::kAdjacent);
    A(n + i, i) = 1, A(n + i, n + i) = -1, A(n + i, 2 * n + i) = -1;
    A(2 * n + i, 2 * n + i) = 1, A(2 * n + i, 3 * n + i) = -kEps[i], A(2 * n + i, n + i) = kEps[i];
    if (i == 3) {
      A(3 * n + i, 2 * n + i) = 1;
    } else {
      A(3 * n + i, 3 * n + i) = 1;
      b(3 * n + i) = sigma * std::pow(kT[i], 4);
    }
  }
  const Eigen::VectorXd x = A.fullPivLu().solve(b);
  Reference r{};
  for (int i = 0; i < n; ++i) {
    r.J[i] = x(i);
    r.q[i] = x(2 * n + i);
    r.T[i] = std::pow(x(3 * n + i) / sigma, 0.25);
  }
  return r;
}

// A CSV as columns by header name (numbers; text cells give NaN).
std::map<std::string, std::vector<double>> read_columns(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::stringstream hs(line);
  for (std::string cell; std::getline(hs, cell, ',');) header.push_back(cell);
  std::map<std::string, std::vector<double>> columns;
  while (std::getline(in, line)) {
    std::stringstream ls(line);
    std::size_t k = 0;
    for (std::string cell; std::getline(ls, cell, ',') && k < header.size(); ++k) {
      char* end = nullptr;
      const double v = std::strtod(cell.c_str(), &end);
      columns[header[k]].push_back(end != cell.c_str() ? v : std::nan(""));
    }
  }
  return columns;
}

std::string text_of(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

TEST_CASE("exchange: the unit cube with exact view factors matches the net-radiation method to 1e-6, the balance "
          "closes to rounding and the group table is reciprocal", "[cli][exchange]") {
  const fs::path dir = scratch_dir("exchange_cube");
  const fs::path scene = write_cube(dir);
  const fs::path csv = dir / "x.csv", json = dir / "x.json", groups = dir / "g.csv", factors = dir / "gf.csv";
  const Run r = run("exchange " + scene.string() + " --analytic --solver direct --csv " + csv.string() + " --json " +
                    json.string() + " --groups " + groups.string() + " --group-factors " + factors.string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  const Reference ref = reference();
  auto c = read_columns(csv);
  REQUIRE(c["J"].size() == 6);
  double q_scale = 0;
  for (double q : ref.q) q_scale = std::max(q_scale, std::abs(q));
  for (int i = 0; i < 6; ++i) {
    INFO("face " << i << ": J " << c["J"][i] << " vs " << ref.J[i] << ", q " << c["q"][i] << " vs " << ref.q[i]
                 << ", T " << c["T"][i] << " vs " << ref.T[i]);
    CHECK(std::abs(c["J"][i] - ref.J[i]) <= 1e-6 * ref.J[0]);
    CHECK(std::abs(c["q"][i] - ref.q[i]) <= 1e-6 * q_scale);
    CHECK(std::abs(c["Q"][i] - ref.q[i]) <= 1e-6 * q_scale);  // unit areas, metres
    CHECK(std::abs(c["T"][i] - ref.T[i]) <= 1e-6 * ref.T[i]);
  }
  CHECK(c["q"][3] == 0.0);
  const auto j = nlohmann::json::parse(text_of(json));
  const auto& x = j.at("exchange");
  INFO(x.dump());
  CHECK(std::abs(x.at("sum_Q").get<double>()) <= 1e-6 * q_scale);
  CHECK(std::abs(x.at("balance_residual").get<double>()) <= 1e-6 * q_scale);
  CHECK(x.at("to_ambient").get<double>() <= 1e-6 * q_scale);
  CHECK(x.at("group_reciprocity_defect").get<double>() < 1e-6);
  // The group factors: one object per face, F_GH the face-to-face view factor, rows summing to 1.
  const std::string table = text_of(factors);
  CHECK(table.rfind("from,to,F,exchange_area", 0) == 0);
  std::map<std::string, double> row_sum;
  std::istringstream lines(table);
  std::string line;
  std::getline(lines, line);
  int entries = 0;
  while (std::getline(lines, line)) {
    std::stringstream ls(line);
    std::string from, to, F;
    std::getline(ls, from, ',');
    std::getline(ls, to, ',');
    std::getline(ls, F, ',');
    row_sum[from] += std::stod(F);
    if (from == "x0" && to == "x1") CHECK(std::abs(std::stod(F) - radwalk::test::kOpposite) < 1e-6);
    if (from == "x0" && to == "y1") CHECK(std::abs(std::stod(F) - radwalk::test::kAdjacent) < 1e-6);
    ++entries;
  }
  CHECK(entries == 6 * 7);  // 6 x 6 and the ambient row of each
  for (const auto& [name, sum] : row_sum) {
    INFO(name);
    CHECK(std::abs(sum - 1) < 1e-6);
  }
  CHECK(text_of(groups).rfind("object,area,Q,Q_se,T_radiant,sky,back", 0) == 0);
}

TEST_CASE("exchange: the traced route agrees with the analytic one within its error bars", "[cli][exchange]") {
  const fs::path dir = scratch_dir("exchange_traced");
  const fs::path scene = write_cube(dir);
  const fs::path exact = dir / "exact.csv", traced = dir / "traced.csv";
  const std::string common = "exchange " + scene.string() + " --max-edge 0.5 --solver direct";
  Run r = run(common + " --analytic --csv " + exact.string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  r = run(common + " --rays 4000 --seed 3 --csv " + traced.string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  auto a = read_columns(exact), t = read_columns(traced);
  const std::size_t n = a["q"].size();
  REQUIRE(n == 24);
  REQUIRE(t["q"].size() == n);
  // The known-temperature patches are compared by q, the re-radiating ones by T; family-wise alpha = 0.01, Sidak.
  const double alpha = 0.01, z_crit = radwalk::z_critical(radwalk::sidak(alpha, n));
  double worst = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const bool given = t["temperature_given"][i] == 1;
    const double d = given ? t["q"][i] - a["q"][i] : t["T"][i] - a["T"][i];
    const double se = given ? t["q_se"][i] : t["T_se"][i];
    REQUIRE(se > 0);
    const double z = d / se;
    worst = std::max(worst, std::abs(z));
    INFO("patch " << i << ": z = " << z << " (d = " << d << ", se = " << se << ")");
    CHECK(std::abs(z) <= z_crit);
  }
  // The test can fail: the analytic answer moved by 1 % of q at the first patch is rejected.
  const double moved = 0.01 * a["q"][0] / t["q_se"][0];
  INFO("largest |z| " << worst << ", critical " << z_crit << ", a 1 % shift gives z = " << moved);
  CHECK(std::abs(moved) > z_crit);
}

TEST_CASE("exchange: missing or contradictory thermal properties, lengths not in metres and thermal --set in other "
          "commands are refused in one line", "[cli][exchange]") {
  const fs::path dir = scratch_dir("exchange_refusals");
  const fs::path scene = write_cube(dir);
  Run r = run("exchange " + source("meshes/cube.obj"));
  CHECK(r.exit_code == 2);
  CHECK(r.out.find("has no emissivity: add 'radwalk_emissivity E'") != std::string::npos);
  r = run("exchange " + scene.string() + " --set t2.heat_flux=5 --set t2.temperature=300 --set t0.emissivity=0 --analytic");
  CHECK(r.exit_code == 2);
  CHECK(r.out.find("emissivity 0 out of range") != std::string::npos);
  r = run("exchange " + scene.string() + " --unit mm --analytic");
  CHECK(r.exit_code == 2);
  CHECK(r.out.find("use --unit mm --scale 0.001") != std::string::npos);
  r = run("solve " + scene.string() + " --set t0.temperature=300");
  CHECK(r.exit_code == 2);
  CHECK(r.out.find("read by 'radwalk exchange' only") != std::string::npos);
  r = run("exchange " + scene.string() + " --analytic --solver direct --tol 1e-9");
  CHECK(r.exit_code == 2);
  // Every surface given a flux, nothing open: no unique temperatures.
  std::string all_flux;
  for (int i = 0; i < 6; ++i) all_flux += " --set t" + std::to_string(i) + ".heat_flux=0";
  r = run("exchange " + scene.string() + " --analytic" + all_flux);
  CHECK(r.exit_code == 2);
  CHECK(r.out.find("determined only up to a constant") != std::string::npos);
  // --set overrides the file: face 0 at 300 K like face 1 changes the answer.
  const fs::path csv = dir / "x.csv";
  r = run("exchange " + scene.string() + " --analytic --set t0.temperature=300 --csv " + csv.string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  CHECK(read_columns(csv)["T"][0] == 300);
}

TEST_CASE("exchange: a block's bottom lying on the floor is a contact patch, reported in W and left out with "
          "--contact-faces exclude, and the balance closes within its error either way", "[cli][exchange]") {
  const fs::path dir = scratch_dir("exchange_contact");
  {
    std::ofstream mtl(dir / "c.mtl");
    mtl << "newmtl wall\nradwalk_emissivity 0.9\nradwalk_temperature 293\n"
           "newmtl block\nradwalk_emissivity 0.8\nradwalk_temperature 330\n";
    std::ofstream obj(dir / "c.obj");
    obj << "mtllib c.mtl\n";
    // A 2 m room facing in, a 0.5 m block facing out standing on its floor (z = 0).
    const auto box = [&](const char* name, const char* mat, double x0, double x1, double z1, bool inward, int base) {
      obj << "o " << name << "\nusemtl " << mat << "\n";
      const double y0 = x0, y1 = x1;
      obj << "v " << x0 << " " << y0 << " 0\nv " << x1 << " " << y0 << " 0\nv " << x1 << " " << y1 << " 0\nv " << x0
          << " " << y1 << " 0\nv " << x0 << " " << y0 << " " << z1 << "\nv " << x1 << " " << y0 << " " << z1
          << "\nv " << x1 << " " << y1 << " " << z1 << "\nv " << x0 << " " << y1 << " " << z1 << "\n";
      const int f[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};
      for (const auto& q : f) {
        obj << "f";
        for (int k = 0; k < 4; ++k) obj << " " << base + 1 + q[inward ? 3 - k : k];
        obj << "\n";
      }
    };
    box("room", "wall", 0, 2, 2, true, 0);
    box("block", "block", 0.5, 1.0, 0.5, false, 8);
  }
  nlohmann::json x[2];
  const char* modes[2] = {"include", "exclude"};
  for (int k = 0; k < 2; ++k) {
    const fs::path json = dir / (std::string(modes[k]) + ".json");
    const Run r = run("exchange " + (dir / "c.obj").string() + " --rays 20000 --solver direct --contact-faces " +
                      modes[k] + " --json " + json.string());
    INFO(r.out);
    REQUIRE(r.exit_code == 0);
    x[k] = nlohmann::json::parse(text_of(json)).at("exchange");
    INFO(x[k].dump());
    CHECK(x[k].at("contact_patches").get<int>() == 1);
    // The balance: the residual within 3.5 of its standard errors (alpha about 5e-4 per run).
    CHECK(std::abs(x[k].at("balance_residual").get<double>()) <= 3.5 * x[k].at("balance_residual_se").get<double>());
  }
  CHECK(x[0].at("contact_radiated").get<double>() > 100);  // the bottom radiates through the floor (about 134 W)
  CHECK(x[1].at("contact_radiated").get<double>() == 0);
  CHECK(x[1].at("sum_Q").get<double>() < x[0].at("sum_Q").get<double>() - 100);
}

// Random walks solve the net-radiation system where they converge (every rho < 1): on the same traced F (the same
// seed) the walks' J differs from the direct solve's by the walks' own noise only, which the reported J_se covers
// (it adds the form factors' noise, so the test is conservative): |J_walk - J_direct| <= z J_se_walk per patch,
// Sidak over the patches at family-wise alpha = 0.01. A re-radiating face (rho = 1) makes the walks endless: one
// line, exit 2.
TEST_CASE("exchange: random walks agree with the direct solve of the same F, and are refused for re-radiating faces",
          "[cli][exchange]") {
  const fs::path dir = scratch_dir("exchange_walks");
  const fs::path direct = dir / "direct.csv", walks = dir / "walks.csv";
  const std::string common = "exchange " + source("meshes/cube.obj") +
                             " --max-edge 0.5 --rays 4000 --seed 3 --set light.emissivity=0.9"
                             " --set light.temperature=600 --set white.emissivity=0.8 --set white.temperature=300";
  Run r = run(common + " --solver direct --csv " + direct.string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  r = run(common + " --solver random-walk --walks-per-patch 20000 --csv " + walks.string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  auto d = read_columns(direct), w = read_columns(walks);
  const std::size_t n = d["J"].size();
  REQUIRE(n == 24);
  REQUIRE(w["J"].size() == n);
  const double z_crit = radwalk::z_critical(radwalk::sidak(0.01, n));
  for (std::size_t i = 0; i < n; ++i) {
    const double z = (w["J"][i] - d["J"][i]) / w["J_se"][i];
    INFO("patch " << i << ": J " << w["J"][i] << " against " << d["J"][i] << ", z = " << z);
    CHECK(std::abs(z) <= z_crit);
    CHECK(w["J_se"][i] > d["J_se"][i]);  // the walks add their own error
  }
  // The test can fail: J moved by 10 % at the first patch is rejected.
  CHECK(0.1 * d["J"][0] / w["J_se"][0] > z_crit);

  const fs::path thermal = write_cube(dir);
  r = run("exchange " + thermal.string() + " --max-edge 0.5 --rays 1000 --solver random-walk");
  INFO(r.out);
  CHECK(r.exit_code == 2);
  CHECK(r.out.find("walks might never end") != std::string::npos);
}
