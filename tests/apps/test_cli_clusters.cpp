// End-to-end: radwalk solve --hierarchical --hierarchical-clusters (hierarchy/cluster_tree.h): the JSON's cluster
// count and memory, and the refusals of what cannot be honoured.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "radwalk_runner.h"

namespace fs = std::filesystem;

namespace {

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

}  // namespace

TEST_CASE("radwalk solve --hierarchical-clusters: clusters counted in the JSON, refusals", "[cli]") {
  const fs::path dir = scratch_dir("cli_clusters_test");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string scene = source("meshes/cornell_box.obj");
  const std::string common = " --hierarchical --hierarchical-tol 0.01 --hierarchical-rays 20000 "
                             "--discretisation-directions 2 --json ";
  const Run off = run("solve " + scene + common + (dir / "off.json").string());
  const Run on = run("solve " + scene + common + (dir / "on.json").string() +
                     " --hierarchical-clusters on --hierarchical-cluster-ratio 0.5");
  INFO(off.out << on.out);
  REQUIRE(off.exit_code == 0);
  REQUIRE(on.exit_code == 0);
  const auto h_off = read_json(dir / "off.json")["hierarchy"], h_on = read_json(dir / "on.json")["hierarchy"];
  CHECK(h_off["clusters"] == 0);
  const std::size_t clusters = h_on["clusters"];
  CHECK(clusters >= 6);             // at least one per orientation group of the box's 37 faces
  CHECK(clusters <= 2 * 37);        // a binary tree over 37 patches
  CHECK(h_on["cluster_deposits"].get<long>() > 0);
  CHECK(h_on["memory_bytes"].get<std::size_t>() > h_off["memory_bytes"].get<std::size_t>());
  // What cannot be honoured is refused in one line.
  const Run estimate = run("solve " + scene + " --hierarchical --hierarchical-refine estimate "
                           "--hierarchical-max-leaves 100 --hierarchical-clusters on");
  CHECK(estimate.exit_code != 0);
  CHECK(estimate.out.find("--hierarchical-clusters on cannot be combined with --hierarchical-refine estimate") !=
        std::string::npos);
  const Run ratio = run("solve " + scene + " --hierarchical --hierarchical-cluster-ratio 0.5");
  CHECK(ratio.exit_code != 0);
  CHECK(ratio.out.find("--hierarchical-cluster-ratio") != std::string::npos);
  const Run plain = run("solve " + scene + " --hierarchical-clusters on");
  CHECK(plain.exit_code != 0);
  CHECK(plain.out.find("--hierarchical-clusters does not apply here (used only with --hierarchical, or "
                       "--target-error on its default route") != std::string::npos);
  fs::remove_all(dir);
}
