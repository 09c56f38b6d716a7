// The default camera of `pathtrace --image` is fitted to the scene (apps/scene_camera.h) and recorded in the JSON
// summary; an image whose every pixel is black is warned about.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "radwalk_runner.h"

namespace fs = std::filesystem;

namespace {

fs::path scratch() { return scratch_dir("cli_camera"); }

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

std::array<double, 3> vec(const nlohmann::json& j) { return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()}; }

}  // namespace

TEST_CASE("pathtrace: a closed room is rendered from inside with the default camera, not black", "[cli][camera]") {
  const fs::path json = scratch() / "cube.json";
  const Run r = run("pathtrace " + source("meshes/cube.obj") + " --image " + (scratch() / "cube.png").string() +
                    " --spp 4 --width 32 --height 32 --json " + json.string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("is black") == std::string::npos);
  const auto j = read_json(json);
  CHECK(j["camera"]["source"] == "inside");
  CHECK(j["camera"]["vertical_fov_deg"].get<double>() == Approx(60));
  for (const double x : vec(j["camera"]["position"])) {  // inside the unit cube
    CHECK(x > 0);
    CHECK(x < 1);
  }
  CHECK(vec(j["camera"]["up"]) == std::array<double, 3>{0, 1, 0});
}

TEST_CASE("pathtrace: an open scene is framed from outside, every corner of its box in view", "[cli][camera]") {
  const fs::path json = scratch() / "perp.json";
  const Run r = run("pathtrace " + source("meshes/perpendicular_squares.obj") + " --image " +
                    (scratch() / "perp.png").string() + " --spp 4 --width 32 --height 32 --json " + json.string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("is black") == std::string::npos);
  const auto j = read_json(json);
  CHECK(j["camera"]["source"] == "outside");
  const auto p = vec(j["camera"]["position"]), t = vec(j["camera"]["look_at"]);
  const double half = 0.5 * j["camera"]["vertical_fov_deg"].get<double>() * M_PI / 180;
  double axis[3], n = 0;
  for (int k = 0; k < 3; ++k) {
    axis[k] = t[k] - p[k];
    n += axis[k] * axis[k];
  }
  for (int c = 0; c < 8; ++c) {  // the squares' bounding box is the unit cube
    const double q[3] = {double(c & 1), double((c >> 1) & 1), double((c >> 2) & 1)};
    double dot = 0, m = 0;
    for (int k = 0; k < 3; ++k) {
      dot += (q[k] - p[k]) * axis[k];
      m += (q[k] - p[k]) * (q[k] - p[k]);
    }
    INFO("corner " << c);
    CHECK(std::acos(dot / std::sqrt(n * m)) <= half);
  }
}

TEST_CASE("pathtrace: an image with every pixel black is warned about (a scene with no light)", "[cli][camera]") {
  const fs::path obj = scratch() / "dark.obj", mtl = scratch() / "dark.mtl", json = scratch() / "dark.json";
  std::ofstream(mtl) << "newmtl white\nKd 0.5 0.5 0.5\n";
  std::ofstream(obj) << "mtllib dark.mtl\nv 0 0 0\nv 0 0 1\nv 1 0 1\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 1 1 1\nv 0 1 1\n"
                        "usemtl white\nf 1 2 3 4\nf 5 6 7 8\nf 1 5 8 2\nf 4 3 7 6\nf 1 4 6 5\nf 2 8 7 3\n";
  const Run r = run("pathtrace " + obj.string() + " --image " + (scratch() / "dark.png").string() +
                    " --spp 2 --width 16 --height 16 --json " + json.string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("every pixel of") != std::string::npos);
  bool recorded = false;
  const auto summary = read_json(json);
  for (const auto& w : summary["warnings"]) recorded |= w.get<std::string>().find("is black") != std::string::npos;
  CHECK(recorded);
  // The Cornell box keeps its own camera (docs/reference-data.md).
  const fs::path cb = scratch() / "cb.json";
  REQUIRE(run("pathtrace " + source("meshes/cornell_box.obj") + " --image " + (scratch() / "cb.png").string() +
              " --spp 2 --width 8 --height 8 --json " + cb.string())
              .exit_code == 0);
  const auto c = read_json(cb)["camera"];
  CHECK(c["source"] == "cornell_box");
  CHECK(vec(c["position"]) == std::array<double, 3>{278, 273, -800});
}

TEST_CASE("measure --response camera: the JSON camera has the keys of pathtrace's (schema 2)", "[cli][camera]") {
  const fs::path mj = scratch() / "measure_cam.json", pj = scratch() / "pathtrace_cam.json";
  const std::string cube = source("meshes/cube.obj");
  const Run m = run("measure " + cube + " --response camera --method shoot-collision --walks 200 --width 16 "
                    "--height 8 --rays 100 -q --json " + mj.string());
  const Run p = run("pathtrace " + cube + " --image " + (scratch() / "cam.png").string() +
                    " --spp 2 --width 16 --height 8 -q --json " + pj.string());
  INFO(m.out << p.out);
  REQUIRE(m.exit_code == 0);
  REQUIRE(p.exit_code == 0);
  const auto a = read_json(mj)["camera"], b = read_json(pj)["camera"];
  for (const char* key : {"position", "look_at", "direction", "up", "vertical_fov_deg", "width", "height", "source"}) {
    INFO(key);
    REQUIRE(a.contains(key));
    CHECK(a[key] == b[key]);  // the same default camera, the same film size
  }
  CHECK(a.size() == b.size());
  CHECK(a["width"] == 16);
  CHECK(a["height"] == 8);
}
