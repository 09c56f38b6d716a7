// CSV and JSON outputs parse back with the promised columns and values.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "io/csv_writer.h"
#include "io/obj_writer.h"
#include "io/run_summary.h"
#include "mesh/read_scene.h"
#include "patch/patch_builder.h"
#include "core/rng.h"
#include "support/csv_reference.h"

using namespace radwalk;

static std::vector<std::vector<std::string>> read_csv(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.push_back("");
    rows.push_back(cells);
  }
  return rows;
}

TEST_CASE("patch CSV has the documented columns and values", "[io][csv]") {
  PatchBuilder b;
  const int m = b.add_material("m", Rgb(0.73, 0.5, 0.25), Rgb(0, 0, 1));
  b.add_quad({0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}, m);
  const PatchSet p = b.build();
  PatchRgb B(1, 3);
  B << 1, 2, std::numeric_limits<double>::quiet_NaN();
  const auto path = (std::filesystem::temp_directory_path() / "radwalk_test.csv").string();
  write_patch_csv(path, p, {rgb_field("B", B), scalar_field("row_sum", {0.5})});
  const auto rows = read_csv(path);
  REQUIRE(rows.size() == 2);
  const std::vector<std::string> expected = {"patch", "face",  "area",  "cx",  "cy",  "cz",  "nx",  "ny",
                                             "nz",    "rho_r", "rho_g", "rho_b", "E_r", "E_g", "E_b", "object",
                                             "group", "material", "B_r", "B_g", "B_b", "row_sum"};
  CHECK(rows[0] == expected);
  REQUIRE(rows[1].size() == expected.size());
  CHECK(std::stod(rows[1][2]) == Approx(2.0));
  CHECK(std::stod(rows[1][3]) == Approx(1.0));
  CHECK(std::stod(rows[1][9]) == 0.73);
  CHECK(std::stod(rows[1][14]) == Approx(kPi));
  CHECK(rows[1][15].empty());  // a generated scene has no object or group names
  CHECK(rows[1][16].empty());
  CHECK(rows[1][17] == "m");
  CHECK(rows[1][20].empty());  // NaN is written as an empty cell, never "nan"
  CHECK(std::stod(rows[1][21]) == 0.5);
  std::filesystem::remove(path);
}

TEST_CASE("CSV numbers are printf's %.12g, character for character", "[io][csv]") {
  std::vector<double> values = {0.0, -0.0, 1.0, -1.0, 0.1, 1.0 / 3.0, 2.0 / 3.0, 1e21, 1e-7, 123456789012.0,
                                1234567890123.0, 9.999999999995e-5, 0.5e-308, 4.9e-324, 1.7976931348623157e308,
                                std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                                -std::numeric_limits<double>::infinity(), 0.73, kPi, 100.0, 1e12, 1e11};
  Rng rng = stream(7, StreamDomain::test, 0, 0);
  for (int k = 0; k < 20000; ++k) {  // random mantissas over exponents from 1e-320 to 1e300, both signs
    const double v = (rng.uniform() - 0.5) * std::pow(10.0, -320.0 + 620.0 * rng.uniform());
    values.push_back(v);
    values.push_back(std::round(v * 1e6) / 1e6);  // short decimals, where rounding ties are likeliest
    values.push_back(double(float(v)));             // float values widened, as B and F are stored
  }
  for (const double v : values) {
    INFO("value " << v);
    CHECK(csv_number(v) == test::printf_csv_number(v));
  }
}

TEST_CASE("patch CSV rows are the former writer's bytes", "[io][csv]") {
  PatchBuilder b;
  const int m = b.add_material("wall, \"white\"", Rgb(0.73, 0.5, 0.25), Rgb(0, 0, 1));
  const int n = b.add_material("plain", Rgb(0.1, 0.2, 0.3), Rgb(0, 0, 0));
  for (int k = 0; k < 40; ++k)
    b.add_quad({0.1 * k, 0, 0}, {0.1 * k + 0.1, 0, 0}, {0.1 * k + 0.1, 1.0 / 3.0, 0}, {0.1 * k, 1.0 / 3.0, 0},
               k % 3 ? m : n);
  const PatchSet p = b.build();
  PatchRgb B(p.size(), 3);
  std::vector<double> se(p.size());
  Rng rng = stream(8, StreamDomain::test, 0, 0);
  for (Eigen::Index i = 0; i < B.rows(); ++i) {
    for (int c = 0; c < 3; ++c) B(i, c) = rng.uniform() * std::pow(10.0, 8 * rng.uniform() - 4);
    se[std::size_t(i)] = i % 7 == 0 ? std::numeric_limits<double>::quiet_NaN() : rng.uniform() * 1e-3;
  }
  const std::vector<CellField> fields = {rgb_field("B", B), scalar_field("B_se", se)};
  const auto path = (std::filesystem::temp_directory_path() / "radwalk_test_rows.csv").string();
  write_patch_csv(path, p, fields, "run-1");
  std::ifstream in(path, std::ios::binary);
  std::string written((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string rows = written.substr(written.find('\n') + 1);  // after the header
  std::ostringstream former;
  test::former_patch_csv_rows(former, p, fields, "run-1");
  CHECK(rows == former.str());
  std::filesystem::remove(path);
}

TEST_CASE("run summary JSON is valid UTF-8 whatever bytes a path or name holds", "[io][json]") {
  // I4: a non-UTF-8 byte in a scene path (recorded in the arguments) was an internal error (exit 4).
  RunSummary s("solve", {"radwalk", "solve", "bad\xff.obj"});
  s.add_warning("material '\xfe' is odd");
  const auto path = (std::filesystem::temp_directory_path() / "radwalk_test_utf8.json").string();
  REQUIRE_NOTHROW(s.write(path));
  std::ifstream in(path);
  const nlohmann::json j = nlohmann::json::parse(in);
  CHECK(j["arguments"][2] == "bad\xef\xbf\xbd.obj");  // U+FFFD
}

TEST_CASE("run summary JSON parses and records timings, warnings and memory", "[io][json]") {
  RunSummary s("solve", {"radwalk", "solve", "scene.obj"});
  s.json()["patches"] = 42;
  s.add_timing("load", 0.25);
  s.add_timing("form factors", 1.5);  // written as a key without spaces
  s.add_warning("face 3: something");
  const auto path = (std::filesystem::temp_directory_path() / "radwalk_test.json").string();
  s.write(path);
  std::ifstream in(path);
  const nlohmann::json j = nlohmann::json::parse(in);
  CHECK(j["command"] == "solve");
  CHECK(j["patches"] == 42);
  CHECK(j["timings_s"]["load"] == 0.25);
  CHECK(j["timings_s"]["form_factors"] == 1.5);
  CHECK(!j["timings_s"].contains("form factors"));
  CHECK(j["schema_version"] == RunSummary::kSchemaVersion);
  CHECK(j["schema_version"].is_number_integer());
  CHECK(j["git_describe"].get<std::string>() == git_describe());
  CHECK(!j["git_describe"].get<std::string>().empty());
  CHECK(j["warnings"][0] == "face 3: something");
  CHECK(j["peak_memory_bytes"].get<long>() > 0);
  CHECK(j["versions"]["embree"].get<std::string>().rfind("3.", 0) == 0);
  std::filesystem::remove(path);
}

TEST_CASE("solution JSON: counts are integers, flags booleans, non-finite numbers null", "[io][json]") {
  Solution s;
  s.method = "direct";
  s.iterations = 12;
  s.walks = 1000;
  s.residual_history = {0.5, std::numeric_limits<double>::infinity()};
  s.info["factorisations"] = 3;
  s.info["dense"] = 1;
  s.info["condition_estimate"] = 4;  // a measurement that happens to be whole stays a number
  s.info["escapes"] = 2.5;           // not whole: kept as it is
  s.info["variance_radius"] = std::numeric_limits<double>::quiet_NaN();
  const nlohmann::json j = solution_json(s);
  CHECK(j["method"] == "direct");
  CHECK(j["status"] == "converged");
  CHECK(j["iterations"].is_number_integer());
  CHECK(j["walks_total"] == 1000);
  CHECK(j["residual"].is_null());  // not computed
  CHECK(j["residual_history"][0] == 0.5);
  CHECK(j["residual_history"][1].is_null());
  CHECK(j["info"]["factorisations"].is_number_integer());
  CHECK(j["info"]["factorisations"] == 3);
  CHECK(j["info"]["dense"].is_boolean());
  CHECK(j["info"]["dense"] == true);
  CHECK(j["info"]["condition_estimate"].is_number_float());
  CHECK(j["info"]["escapes"] == 2.5);
  CHECK(j["info"]["variance_radius"].is_null());
}

TEST_CASE("write_obj writes faces in patch order with an MTL beside it", "[io][obj]") {
  PatchBuilder b;
  const int m = b.add_material("wall", Rgb(0.73, 0.5, 0.25), Rgb(0, 0, 1));
  b.add_quad({0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}, m);
  b.add_triangle({0, 0, 1}, {1, 0, 1}, {0, 1, 1}, m);
  const PatchSet p = b.build();
  const auto dir = std::filesystem::temp_directory_path();
  write_obj((dir / "radwalk_test_out.obj").string(), p);
  std::ifstream obj(dir / "radwalk_test_out.obj"), mtl(dir / "radwalk_test_out.mtl");
  std::stringstream so, sm;
  so << obj.rdbuf();
  sm << mtl.rdbuf();
  CHECK(so.str().find("mtllib radwalk_test_out.mtl") != std::string::npos);
  CHECK(so.str().find("f 1 2 3 4\nf 5 6 7\n") != std::string::npos);
  CHECK(sm.str().find("newmtl wall\nKd 0.72999999999999998 0.5 0.25\nKe 0 0 1\n") != std::string::npos);
}

TEST_CASE("write_obj: a material's roughness survives the round trip", "[io][obj]") {
  // W8: the writer wrote the GGX alpha as Pr, which the reader squares: every round trip squared the roughness.
  PatchBuilder b;
  const int m = b.add_material("brushed", Rgb(0.5, 0.5, 0.5));
  b.add_quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, m);
  PatchSet p = b.build();
  p.materials[0].kind = BsdfKind::microfacet;
  p.materials[0].illum = 3;
  p.materials[0].roughness = 0.3;
  const auto path = (std::filesystem::temp_directory_path() / "radwalk_roughness.obj").string();
  for (int trip = 0; trip < 3; ++trip) {
    write_obj(path, p);
    const Mesh back = read_scene(path);
    REQUIRE(back.materials.size() == 1);
    INFO("round trip " << trip);
    CHECK(back.materials[0].kind == BsdfKind::microfacet);
    CHECK(back.materials[0].roughness == Approx(0.3).epsilon(1e-15));
    p.materials[0].roughness = back.materials[0].roughness;
  }
}
