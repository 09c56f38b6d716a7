// `radwalk exchange` with a closed cavity (docs/heat-exchange.md, "Closed cavities";
// solve/closed_cavities.h): a hollow box of re-radiating faces floating in a room, drawn as furniture models
// draw it (an outer shell facing out, an inner one facing in). The inner faces see only one another, so
// radiation leaves their radiosity undetermined: the run names them in one warning, gives them no J, G, T,
// leaves them out of the box's radiant temperature, and solves the rest exactly as in the same room without
// the inner shell.
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "radwalk_runner.h"

namespace fs = std::filesystem;

namespace {

// A 2 m room (floor at 293 K, eps 0.95; walls and ceiling at 283 K, eps 0.9) with a re-radiating box (q = 0,
// eps 0.85, object "box") of 0.6 m floating at x, y in [0.7, 1.3], z in [0.5, 1.1]: its outer shell (group
// "shell") and, with `hollow`, an inner shell 2 cm inside facing in (group "inside"), written last so that
// the patches of both scenes before it are the same. Read with --orient none: --orient outward would turn the
// inner shell, a closed shell of its own, to face out (into the outer shell's backs).
fs::path write_room(const fs::path& dir, bool hollow) {
  const std::string name = hollow ? "hollow" : "shell";
  std::ofstream mtl(dir / (name + ".mtl"));
  mtl << "newmtl floor\nradwalk_emissivity 0.95\nradwalk_temperature 293\n"
         "newmtl wall\nradwalk_emissivity 0.9\nradwalk_temperature 283\n"
         "newmtl box\nradwalk_emissivity 0.85\nradwalk_heat_flux 0\n";
  std::ofstream obj(dir / (name + ".obj"));
  obj << "mtllib " << name << ".mtl\n";
  int vertices = 0;
  // A box's six faces, corners counter-clockwise seen from outside (from inside when inward); bottom first.
  const auto box = [&](double x0, double x1, double y0, double y1, double z0, double z1, bool inward,
                       const char* bottom_header, const char* rest_header) {
    const double c[8][3] = {{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0},
                            {x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}};
    for (const auto& p : c) obj << "v " << p[0] << " " << p[1] << " " << p[2] << "\n";
    const int f[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};
    for (int k = 0; k < 6; ++k) {
      if (k == 0) obj << bottom_header;
      if (k == 1) obj << rest_header;
      obj << "f";
      for (int j = 0; j < 4; ++j) obj << " " << vertices + 1 + f[k][inward ? 3 - j : j];
      obj << "\n";
    }
    vertices += 8;
  };
  box(0, 2, 0, 2, 0, 2, true, "o floor\nusemtl floor\n", "o walls\nusemtl wall\n");
  box(0.7, 1.3, 0.7, 1.3, 0.5, 1.1, false, "o box\ng shell\nusemtl box\n", "");
  if (hollow) box(0.72, 1.28, 0.72, 1.28, 0.52, 1.08, true, "g inside\n", "");
  return dir / (name + ".obj");
}

// A CSV as rows of cells (no quoted commas in these files) and its header.
struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::size_t column(const std::string& name) const {
    for (std::size_t k = 0; k < header.size(); ++k)
      if (header[k] == name) return k;
    FAIL("no column " << name);
    return 0;
  }
};
Table read_csv(const fs::path& file) {
  Table t;
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, ',')) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    if (t.header.empty())
      t.header = cells;
    else
      t.rows.push_back(cells);
  }
  return t;
}

struct Result {
  nlohmann::json exchange, warnings;
  Table patches, groups;
};
Result exchange_of(const fs::path& scene, const std::string& solver) {
  const std::string out = (scene.parent_path() / (scene.stem().string() + "_" + solver)).string();
  const Run r = run("exchange " + scene.string() + " --max-edge 0.4 --orient none --analytic --solver " +
                    solver + " --discretisation-directions 0 --group-by object --json " + out +
                    ".json --csv " + out + ".csv --groups " + out + "_groups.csv");
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  std::ifstream in(out + ".json");
  std::stringstream text;
  text << in.rdbuf();
  const nlohmann::json j = nlohmann::json::parse(text.str());
  return {j.at("exchange"), j.at("warnings"), read_csv(out + ".csv"), read_csv(out + "_groups.csv")};
}

double number(const std::string& cell) {
  return std::stod(cell);
}

}  // namespace

TEST_CASE(
    "exchange: a closed hollow box's interior is named, given no temperature and left out, and the rest of "
    "the "
    "room is solved as without it",
    "[cli][exchange][cavity]") {
  // Before, the direct solve refused the whole run (I - diag(rho) F singular) and GMRES returned J = 0 inside
  // (T = 0 K), the box's T_radiant 243.90 K instead of its shell's 285.26 K.
  const fs::path dir = scratch_dir("exchange_cavity");
  const fs::path hollow_scene = write_room(dir, true), shell_scene = write_room(dir, false);
  for (const char* solver : {"direct", "gmres"}) {
    INFO("--solver " << solver);
    const Result hollow = exchange_of(hollow_scene, solver);
    const Result shell = exchange_of(shell_scene, solver);
    INFO(hollow.exchange.dump());

    // The interior: 6 faces of 0.56 m, 2 x 2 patches each at --max-edge 0.4.
    const std::size_t interior = 24, common = shell.patches.rows.size();
    REQUIRE(hollow.patches.rows.size() == common + interior);
    const nlohmann::json& cavities = hollow.exchange.at("cavities");
    REQUIRE(cavities.size() == 1);
    CHECK(cavities[0].at("patches").get<std::size_t>() == interior);
    CHECK(std::abs(cavities[0].at("area").get<double>() - 6 * 0.56 * 0.56) <= 1e-9);
    CHECK(cavities[0].at("objects") == nlohmann::json::array({"box"}));
    CHECK(cavities[0].at("groups") == nlohmann::json::array({"inside"}));
    CHECK(cavities[0].at("first_patch").get<std::size_t>() == common);
    CHECK(cavities[0].at("leak").get<double>() < hollow.exchange.at("cavity_leak_threshold").get<double>());
    CHECK(shell.exchange.at("cavities").empty());
    // One warning naming it (its object, group, patches and area).
    int named = 0;
    for (const auto& w : hollow.warnings) {
      const std::string text = w.get<std::string>();
      if (text.find("closed cavity") == std::string::npos) continue;
      ++named;
      CHECK(text.find("24 patches (1.882 m^2)") != std::string::npos);
      CHECK(text.find("'box'") != std::string::npos);
      CHECK(text.find("'inside'") != std::string::npos);
    }
    CHECK(named == 1);

    // Per patch: the interior has no J, G, T (empty cells) and cavity = 1; q and Q are the given 0.
    const Table& h = hollow.patches;
    for (std::size_t i = common; i < h.rows.size(); ++i) {
      INFO("patch " << i);
      for (const char* name : {"J", "G", "T", "J_se", "T_se"}) CHECK(h.rows[i][h.column(name)].empty());
      CHECK(number(h.rows[i][h.column("cavity")]) == 1);
      CHECK(number(h.rows[i][h.column("q")]) == 0);
      CHECK(number(h.rows[i][h.column("Q")]) == 0);
    }
    // The rest: the same patches with the same J, q and T as without the inner shell. The analytic F of these
    // patches is the same in both scenes (the inner shell is hidden inside the outer one); what remains is
    // the solves' rounding on systems of different sizes (relative residuals below 1e-12, --tol for GMRES,
    // and kappa_inf of I - diag(rho) F 4.2 here, with every wall at a given temperature), bounded by 1e-9 of
    // the largest radiosity with room to spare. (Measured: equal to the CSV's 12 digits.)
    const Table& s = shell.patches;
    double scale = 0;
    for (const auto& row : s.rows) scale = std::max(scale, number(row[s.column("J")]));
    REQUIRE(scale > 0);
    for (std::size_t i = 0; i < common; ++i) {
      INFO("patch " << i);
      for (const char* name : {"face", "cx", "cy", "cz", "area"})
        CHECK(h.rows[i][h.column(name)] == s.rows[i][s.column(name)]);
      CHECK(number(h.rows[i][h.column("cavity")]) == 0);
      for (const char* name : {"J", "G", "q"})
        CHECK(std::abs(number(h.rows[i][h.column(name)]) - number(s.rows[i][s.column(name)])) <=
              1e-9 * scale);
      CHECK(std::abs(number(h.rows[i][h.column("T")]) - number(s.rows[i][s.column("T")])) <= 1e-9 * 293);
    }
    // The box's radiant temperature is its outer shell's, as without the interior, within the same rounding.
    const auto box_T = [](const Table& g) {
      for (const auto& row : g.rows)
        if (row[g.column("object")] == "box") return number(row[g.column("T_radiant")]);
      FAIL("no box in the group table");
      return 0.0;
    };
    CHECK(std::abs(box_T(hollow.groups) - box_T(shell.groups)) <= 1e-9 * 293);
    CHECK(box_T(shell.groups) >= 283.0);
    CHECK(box_T(shell.groups) <= 293.0);
    // The energy balance: the cavity exchanges nothing, so it is the same.
    CHECK(std::abs(hollow.exchange.at("sum_Q").get<double>() - shell.exchange.at("sum_Q").get<double>()) <=
          1e-9 * scale * 30);  // 1e-9 of the largest J over the 26.2 m^2 of patches
  }
}

namespace {

// The room of write_room with, instead of the box, a re-radiating box drawn by its inside only (one-sided
// faces facing in, group "inside"; its outside is the faces' absorbing backs) at x, y in [0.72, 1.28], z in
// [0.52, 1.08], its top pierced by a square hole of side `hole` at its centre (the top drawn as four quads
// around it).
fs::path write_pierced_room(const fs::path& dir, double hole) {
  const std::string name = "pierced" + std::to_string(int(std::lround(hole * 1000)));
  std::ofstream mtl(dir / (name + ".mtl"));
  mtl << "newmtl floor\nradwalk_emissivity 0.95\nradwalk_temperature 293\n"
         "newmtl wall\nradwalk_emissivity 0.9\nradwalk_temperature 283\n"
         "newmtl box\nradwalk_emissivity 0.85\nradwalk_heat_flux 0\n";
  std::ofstream obj(dir / (name + ".obj"));
  obj << "mtllib " << name << ".mtl\n";
  int vertices = 0;
  // A quad through four points, in the order given (counter-clockwise seen from where it faces).
  const auto quad = [&](const std::vector<std::array<double, 3>>& p) {
    for (const auto& v : p) obj << "v " << v[0] << " " << v[1] << " " << v[2] << "\n";
    obj << "f " << vertices + 1 << " " << vertices + 2 << " " << vertices + 3 << " " << vertices + 4 << "\n";
    vertices += 4;
  };
  // The room: faces facing in.
  obj << "o floor\nusemtl floor\n";
  quad({{0, 0, 0}, {0, 2, 0}, {2, 2, 0}, {2, 0, 0}});
  obj << "o walls\nusemtl wall\n";
  quad({{0, 0, 2}, {2, 0, 2}, {2, 2, 2}, {0, 2, 2}});
  quad({{0, 0, 0}, {2, 0, 0}, {2, 0, 2}, {0, 0, 2}});
  quad({{2, 2, 0}, {0, 2, 0}, {0, 2, 2}, {2, 2, 2}});
  quad({{2, 0, 0}, {2, 2, 0}, {2, 2, 2}, {2, 0, 2}});
  quad({{0, 2, 0}, {0, 0, 0}, {0, 0, 2}, {0, 2, 2}});
  // The box's inside: the bottom and the four sides face in, the top (facing down) around the hole.
  const double a = 0.72, b = 1.28, z0 = 0.52, z1 = 1.08, h0 = 1.0 - hole / 2, h1 = 1.0 + hole / 2;
  obj << "o box\ng inside\nusemtl box\n";
  quad({{a, a, z0}, {b, a, z0}, {b, b, z0}, {a, b, z0}});
  quad({{a, a, z0}, {a, a, z1}, {b, a, z1}, {b, a, z0}});
  quad({{b, b, z0}, {b, b, z1}, {a, b, z1}, {a, b, z0}});
  quad({{b, a, z0}, {b, a, z1}, {b, b, z1}, {b, b, z0}});
  quad({{a, b, z0}, {a, b, z1}, {a, a, z1}, {a, a, z0}});
  quad({{a, a, z1}, {a, h0, z1}, {b, h0, z1}, {b, a, z1}});
  quad({{a, h1, z1}, {a, b, z1}, {b, b, z1}, {b, h1, z1}});
  quad({{a, h0, z1}, {a, h1, z1}, {h0, h1, z1}, {h0, h0, z1}});
  quad({{h1, h0, z1}, {h1, h1, z1}, {b, h1, z1}, {b, h0, z1}});
  return dir / (name + ".obj");
}

}  // namespace

TEST_CASE(
    "exchange: a re-radiating box with a hole is a closed cavity below the leak threshold and solved above "
    "it",
    "[cli][exchange][cavity]") {
  // The near-closed rule (docs/heat-exchange.md, "Closed cavities"): the box's inside C sends out through the
  // hole exactly what the hole's plane receives from it, A_hole (reciprocity, F_hole->C = 1), so its leak
  // fraction is at least out / A_C = A_hole / A_C, A_C = 6 * 0.56^2 - A_hole. A 1 cm hole: 5.3e-5 < 1e-4, a
  // cavity; a 10 cm hole: 5.3e-3, solved. The analytic F between the box's patches is the exact polygon form
  // factor (nothing occludes them) stored in float: each of the about 24 entries of a row rounded by 2^-24
  // relative, so `out` is A_hole within A_C * 24 * 2^-24 = 2.7e-6 m^2.
  const fs::path dir = scratch_dir("exchange_cavity_hole");
  for (const double hole : {0.01, 0.1}) {
    const double A_hole = hole * hole, A_C = 6 * 0.56 * 0.56 - A_hole;
    const bool closed = A_hole / A_C < 1e-4;
    std::vector<std::vector<std::string>> T_by_solver;
    for (const char* solver : {"direct", "gmres"}) {
      INFO("hole " << hole << " m, --solver " << solver);
      const Result r = exchange_of(write_pierced_room(dir, hole), solver);
      const nlohmann::json& cavities = r.exchange.at("cavities");
      REQUIRE(cavities.size() == (closed ? 1u : 0u));
      const Table& t = r.patches;
      std::vector<std::string> T;
      // The inside's patches (the box is an open shell, made two-sided: its back patches, side 1, face the room).
      for (const auto& row : t.rows)
        if (row[t.column("group")] == "inside" && row[t.column("side")] == "0") T.push_back(row[t.column("T")]);
      REQUIRE(!T.empty());
      if (closed) {
        CHECK(cavities[0].at("groups") == nlohmann::json::array({"inside"}));
        CHECK(cavities[0].at("patches").get<std::size_t>() == T.size());
        const double leak = cavities[0].at("leak").get<double>();
        CHECK(leak >= (A_hole - A_C * 24 * std::ldexp(1.0, -24)) / A_C);
        CHECK(leak < 1e-4);
        for (const std::string& cell : T) CHECK(cell.empty());
      } else {
        for (const std::string& cell : T) CHECK(!cell.empty());
      }
      T_by_solver.push_back(T);
    }
    // Solved, the box's temperatures are determined: the direct LU and GMRES give the same, to 1e-9 relative
    // (the solves' rounding over a leak of 5e-3: kappa ~ 1 / lambda = 2e2 times a residual below 1e-12);
    // before, a closed block made the direct solve refuse and GMRES return J = 0.
    if (!closed)
      for (std::size_t i = 0; i < T_by_solver[0].size(); ++i)
        CHECK(std::abs(number(T_by_solver[0][i]) - number(T_by_solver[1][i])) <= 1e-9 * 293);
  }
}
