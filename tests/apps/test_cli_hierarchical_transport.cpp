// End-to-end: radwalk solve --hierarchical --target-error --hierarchical-transport (hierarchy/
// hierarchical_target_error.h): the JSON records the transport, the form-factor transport reports its F, and what
// cannot be honoured is refused in one line with a non-zero exit.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "radwalk_runner.h"

namespace fs = std::filesystem;

TEST_CASE("radwalk solve --hierarchical-transport: recorded, and refused where it cannot be honoured", "[cli]") {
  const fs::path dir = scratch_dir("cli_hierarchical_transport_test");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string scene = source("meshes/cornell_box.obj");
  const std::string common = " --hierarchical --target-error 0.2 --rays 100 --discretisation-directions 2 --json ";
  const Run ff = run("solve " + scene + common + (dir / "ff.json").string() + " --hierarchical-transport form-factors");
  const Run rays = run("solve " + scene + common + (dir / "rays.json").string() + " --hierarchical-transport rays");
  INFO(ff.out << rays.out);
  REQUIRE(ff.exit_code == 0);
  REQUIRE(rays.exit_code == 0);
  std::ifstream ff_in(dir / "ff.json"), rays_in(dir / "rays.json");
  const auto j_ff = nlohmann::json::parse(ff_in), j_rays = nlohmann::json::parse(rays_in);
  CHECK(j_ff["target_error"]["transport"] == "form-factors");
  CHECK(j_ff["hierarchy"]["transport"] == "form-factors");
  CHECK(j_rays["target_error"]["transport"] == "rays");
  CHECK(j_ff["error_estimate"]["statistical"]["relative"].get<double>() > 0);
  CHECK(j_rays["error_estimate"]["statistical"]["relative"].get<double>() > 0);

  const auto refused = [&](const std::string& options, const std::string& message) {
    const Run r = run("solve " + scene + " " + options);
    INFO(options << "\n" << r.out);
    CHECK(r.exit_code != 0);
    CHECK(r.out.find(message) != std::string::npos);
  };
  // Without --target-error (or on its uniform route) there is no step whose leaves it could solve.
  const std::string only = "--hierarchical-transport does not apply here (used only with --target-error on its "
                           "default route, the hierarchical one)";
  refused("--hierarchical --hierarchical-transport rays", only);
  refused("--target-error 0.1 --target-route uniform --hierarchical-transport form-factors", only);
  // The stochastic Jacobi's own options mean nothing to the form-factor transport.
  refused("--hierarchical --target-error 0.1 --hierarchical-points 64",
          "--hierarchical-points does not apply here (used only by the hierarchical stochastic Jacobi");
  refused("--hierarchical --target-error 0.1 --hierarchical-transport form-factors --hierarchical-replicates 8",
          "--hierarchical-replicates does not apply here");
  // Form-factor options mean nothing to the rays.
  refused("--hierarchical --target-error 0.1 --hierarchical-transport rays --emitter-columns 64",
          "--emitter-columns does not apply here");
  refused("--hierarchical --target-error 0.1 --hierarchical-transport walks", "--hierarchical-transport");
  fs::remove_all(dir);
}
