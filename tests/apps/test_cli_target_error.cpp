// `radwalk solve --target-error E` end to end (apps/target_error.h, apps/hierarchical_target_error.h,
// docs/accuracy.md "Accuracy on request"): the hierarchical route by default, the uniform one with --target-route
// uniform; a reachable target is reached, its steps are in the JSON and the final estimate is at most E; a patch
// budget too small stops it with exit 1, one line saying what was reached, and the files of the last solution
// written; the options it chooses itself are refused with exit 2.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "radwalk_runner.h"
#include "run_id_reader.h"

namespace fs = std::filesystem;

TEST_CASE("solve --target-error --target-route uniform reaches a reachable target and lists its steps",
          "[cli][target_error]") {
  const fs::path dir = scratch_dir("target_error");
  const std::string scene = source("meshes/cornell_box.obj") + " --max-edge 200 --rays 300 --target-route uniform";
  const fs::path json = dir / "t.json", csv = dir / "t.csv";
  const Run r = run("solve " + scene + " --target-error 0.02 --json " + json.string() + " --csv " + csv.string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  const nlohmann::json j = nlohmann::json::parse(file_text(json));
  const auto& t = j.at("target_error");
  CHECK(t.at("route") == "uniform");
  CHECK(t.at("reached").get<bool>());
  CHECK(t.at("stop_reason") == "target reached");
  REQUIRE(t.at("steps").size() >= 2);  // 125 patches of at most 200 mm (the floor cut along the blocks): 2.8 %
  const auto& last = t.at("steps").back();
  CHECK(last.at("total").get<double>() <= 0.02);
  CHECK(last.at("total").get<double>() == Approx(j.at("error_estimate").at("total").at("relative").get<double>()));
  CHECK(j.at("patches").get<std::size_t>() == last.at("patches").get<std::size_t>());
  CHECK(fs::exists(csv));
}

TEST_CASE("solve --target-error cuts along the contacts though no --max-edge is given",
          "[cli][target_error]") {
  // --target-error splits the input faces itself, so the contact cut (the default, and --contact-cut said
  // explicitly) is made first; before, without --max-edge it was ignored (contact_cut false, no face cut).
  // --no-contact-cut keeps the plain split.
  const fs::path dir = scratch_dir("target_error_contacts");
  const fs::path json = dir / "t.json";
  for (const std::string option : {"", " --contact-cut", " --no-contact-cut"}) {
    const Run r = run("solve " + source("meshes/cornell_box.obj") + " --rays 300 --target-error 0.2" + option +
                      " --json " + json.string());
    INFO(option << "\n" << r.out);
    REQUIRE(r.exit_code == 0);
    const nlohmann::json j = nlohmann::json::parse(file_text(json));
    const bool cut = option != " --no-contact-cut";
    CHECK(j.at("contact_cut").get<bool>() == cut);
    // The floor faces under the two blocks (test_contact).
    CHECK(j.at("contact_faces_cut").get<std::size_t>() == (cut ? 7u : 0u));
  }
}

TEST_CASE("solve --target-error stopped by its patch budget exits 1 with one line and writes the last solution",
          "[cli][target_error]") {
  const fs::path dir = scratch_dir("target_error_budget");
  const fs::path vtp = dir / "b.vtp";
  const Run r = run("solve " + source("meshes/cornell_box.obj") +
                    " --target-route uniform --rays 300 --target-error 0.005 --max-patches 90 -o " + vtp.string());
  INFO(r.out);
  CHECK(r.exit_code == 1);
  CHECK(r.out.find("radwalk: target error 0.5 % not reached (max-patches stopped it after") != std::string::npos);
  CHECK(r.out.find("; the default route (without --target-route uniform) splits elements only where") !=
        std::string::npos);
  CHECK(fs::exists(vtp));
}

// Refused with exit 2 and one line, on either route: the options it chooses itself, clusters (its steps solve the
// leaves unclustered), --hierarchical with --target-route uniform, and the route's own options without
// --target-error or on the other route.
TEST_CASE("solve --target-error refuses the options it chooses itself", "[cli][target_error]") {
  const std::string box = source("meshes/cornell_box.obj"), scene = box + " --target-error 0.05 ";
  for (const std::string route : {"", "--target-route uniform "})
    for (const std::string extra : {"--solver jacobi", "--refine 0.1", "--rays-per-area 1e-3", "--hierarchical-clusters on"}) {
      const Run r = run("solve " + scene + route + extra);
      INFO(route << extra << "\n" << r.out);
      CHECK(r.exit_code == 2);
      CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
    }
  for (const std::string& bad : {box + " --max-seconds 10", box + " --target-route uniform",
                                scene + "--target-route uniform --hierarchical",
                                scene + "--target-route uniform --hierarchical-transport rays",
                                scene + "--target-route uniform --hierarchical-split regular",
                                scene + "--target-route flat"}) {
    const Run r = run("solve " + bad);
    INFO(bad << "\n" << r.out);
    CHECK(r.exit_code == 2);
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
  }
}

// The default route is the hierarchy's: the same leaves and B as --hierarchical says it explicitly.
TEST_CASE("solve --target-error takes the hierarchical route by default", "[cli][target_error]") {
  const fs::path dir = scratch_dir("target_error_route");
  const std::string scene = source("meshes/cornell_box.obj") + " --target-error 0.06 --rays 200 --discretisation-directions 4";
  const fs::path by_default = dir / "d.csv", explicitly = dir / "h.csv", json = dir / "d.json";
  const Run d = run("solve " + scene + " --csv " + by_default.string() + " --json " + json.string());
  INFO(d.out);
  REQUIRE(d.exit_code == 0);
  CHECK(nlohmann::json::parse(file_text(json)).at("target_error").at("route") == "hierarchical");
  const Run h = run("solve " + scene + " --hierarchical --target-route hierarchical --csv " + explicitly.string());
  INFO(h.out);
  REQUIRE(h.exit_code == 0);
  CHECK(csv_without_run_id(file_text(by_default)) == csv_without_run_id(file_text(explicitly)));  // run_id: the command
}

// Through the hierarchy: the steps (leaves, rays a leaf, all their rays, the three errors, seconds) in the JSON, the last
// estimate at most E, one CSV row per leaf, the summary line's estimate (the step lines are notes, silenced by the
// runner's --quiet); a leaf budget too small exits 1 with one
// line; the options the route chooses itself refused with exit 2 and one line.
TEST_CASE("solve --hierarchical --target-error reaches a reachable target and lists its steps", "[cli][target_error]") {
  const fs::path dir = scratch_dir("target_error_hierarchical");
  const fs::path json = dir / "h.json", csv = dir / "h.csv";
  const Run r = run("solve " + source("meshes/cornell_box.obj") + " --hierarchical --target-error 0.06 --rays 200 " +
                    "--discretisation-directions 4 --json " + json.string() + " --csv " + csv.string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  const nlohmann::json j = nlohmann::json::parse(file_text(json));
  const auto& t = j.at("target_error");
  CHECK(t.at("route") == "hierarchical");
  CHECK(t.at("reached").get<bool>());
  REQUIRE(t.at("steps").size() >= 1);
  const auto& last = t.at("steps").back();
  CHECK(last.at("total").get<double>() <= 0.06);
  CHECK(last.at("total").get<double>() == Approx(j.at("error_estimate").at("total").at("relative").get<double>()));
  // All the last step's rays: F's (rays a leaf x leaves) and its estimates' (no split after it, so no band split's).
  const auto& estimates = j.at("error_estimate");
  CHECK(last.at("rays").get<long>() ==
        last.at("rays_per_patch").get<long>() * last.at("leaves").get<long>() +
            estimates.at("discretisation").at("rays").get<long>() +
            estimates.at("statistical").at("calibration_rays").get<long>());
  CHECK(j.at("patches").get<std::size_t>() == last.at("leaves").get<std::size_t>());
  CHECK(j.at("hierarchy").at("leaves").get<std::size_t>() == last.at("leaves").get<std::size_t>());
  const std::string rows = file_text(csv);
  CHECK(static_cast<std::size_t>(std::count(rows.begin(), rows.end(), '\n')) == last.at("leaves").get<std::size_t>() + 1);
  CHECK(r.out.find("estimated error e = ") != std::string::npos);
}

TEST_CASE("solve --hierarchical --target-error: the leaf budget exits 1, the options it chooses refused",
          "[cli][target_error]") {
  const std::string scene = source("meshes/cornell_box.obj") + " --hierarchical --target-error 0.005 --rays 100 ";
  const Run b = run("solve " + scene + "--discretisation-directions 2 --max-patches 70 --max-seconds 3");
  INFO(b.out);
  CHECK(b.exit_code == 1);
  CHECK(b.out.find("radwalk: target error 0.5 % not reached (max-") != std::string::npos);
  CHECK(b.out.find(" leaves and ") != std::string::npos);  // the rays a leaf depend on when the time budget stops it
  CHECK(b.out.find(" rays a leaf") != std::string::npos);
  // The depth bounds, not the budget, stop a run whose marked leaves cannot be split: said so.
  const Run d = run("solve " + scene + "--discretisation-directions 2 --hierarchical-levels 0");
  INFO(d.out);
  CHECK(d.exit_code == 1);
  CHECK(d.out.find("not reached (depth stopped it after") != std::string::npos);
  CHECK(d.out.find("no leaf it would split is above --hierarchical-levels") != std::string::npos);
  for (const std::string extra : {"--hierarchical-tol 0.01", "--hierarchical-rays 1000", "--hierarchical-refine estimate",
                                  "--hierarchical-max-leaves 100", "--solver jacobi", "--rays-per-area 1e-3"}) {
    const Run r = run("solve " + scene + extra);
    INFO(extra << "\n" << r.out);
    CHECK(r.exit_code == 2);
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
  }
}

namespace {

// A room 4 x 3 x 4 m (floor, walls), a light below the ceiling, and a closed box 1.6 x 2 x 0.8 m standing `gap`
// metres from the wall z = 4: the box's back and the wall behind it see each other across the gap, where the
// radiosity falls with the depth, so the box's mean is off by more than the per-patch RMS (2.3 % against 3.1 % at
// 0.02 m with the default start of about 500 patches).
std::string box_by_a_wall(const fs::path& dir, double gap) {
  std::ofstream mtl(dir / "gap.mtl");
  mtl << "newmtl floor\nKd 0.5 0.5 0.5\nnewmtl wall\nKd 0.7 0.7 0.7\nnewmtl box\nKd 0.6 0.6 0.6\n"
         "newmtl light\nKd 0 0 0\nKe 10 10 10\n";
  std::ofstream obj(dir / "gap.obj");
  obj << "mtllib gap.mtl\n";
  int v = 0;
  const auto quad = [&](const std::string& material, const std::array<std::array<double, 3>, 4>& corners) {
    obj << "usemtl " << material << "\n";
    for (const auto& c : corners) obj << "v " << c[0] << " " << c[1] << " " << c[2] << "\n";
    obj << "f " << v + 1 << " " << v + 2 << " " << v + 3 << " " << v + 4 << "\n";
    v += 4;
  };
  quad("floor", {{{0, 0, 0}, {0, 0, 4}, {4, 0, 4}, {4, 0, 0}}});
  quad("wall", {{{0, 3, 0}, {4, 3, 0}, {4, 3, 4}, {0, 3, 4}}});
  quad("wall", {{{0, 0, 0}, {4, 0, 0}, {4, 3, 0}, {0, 3, 0}}});
  quad("wall", {{{0, 0, 4}, {0, 3, 4}, {4, 3, 4}, {4, 0, 4}}});
  quad("wall", {{{0, 0, 0}, {0, 3, 0}, {0, 3, 4}, {0, 0, 4}}});
  quad("wall", {{{4, 0, 0}, {4, 0, 4}, {4, 3, 4}, {4, 3, 0}}});
  quad("light", {{{1.5, 2.99, 0.5}, {2.5, 2.99, 0.5}, {2.5, 2.99, 1.5}, {1.5, 2.99, 1.5}}});
  const double x0 = 1.2, x1 = 2.8, y1 = 2, z1 = 4 - gap, z0 = z1 - 0.8;
  quad("box", {{{x0, y1, z0}, {x0, y1, z1}, {x1, y1, z1}, {x1, y1, z0}}});
  quad("box", {{{x0, 0, z0}, {x0, y1, z0}, {x1, y1, z0}, {x1, 0, z0}}});
  quad("box", {{{x0, 0, z1}, {x1, 0, z1}, {x1, y1, z1}, {x0, y1, z1}}});
  quad("box", {{{x0, 0, z0}, {x0, 0, z1}, {x0, y1, z1}, {x0, y1, z0}}});
  quad("box", {{{x1, 0, z0}, {x1, y1, z0}, {x1, y1, z1}, {x1, 0, z1}}});
  quad("box", {{{x0, 0, z0}, {x1, 0, z0}, {x1, 0, z1}, {x0, 0, z1}}});
  return (dir / "gap.obj").string();
}

}  // namespace

// --target-each (the default: material): a run whose per-patch estimate is within E at its start goes on while a
// material's mean is not, and stops with every material's mean within E; --target-each none stops at once; the
// groups are in the JSON. Refused: an unknown group, --target-each without --target-error, and an explicit group
// with the hierarchy's rays transport (which keeps none by default).
TEST_CASE("solve --target-error holds each material's mean within the target", "[cli][target_error]") {
  const fs::path dir = scratch_dir("target_error_each");
  const std::string box = box_by_a_wall(dir, 0.02), scene = box + " --target-error 0.028 --target-route uniform";
  const std::string hierarchical = box + " --target-error 0.028";
  const fs::path json = dir / "t.json";
  const Run r = run("solve " + scene + " --json " + json.string());
  INFO(r.out);
  REQUIRE(r.exit_code == 0);
  const nlohmann::json j = nlohmann::json::parse(file_text(json));
  const auto& t = j.at("target_error");
  CHECK(t.at("each") == "material");
  REQUIRE(t.at("steps").size() >= 2);
  const auto& first = t.at("steps").front();
  CHECK(first.at("total").get<double>() <= 0.028);  // the per-patch target alone would stop here
  CHECK(first.at("groups_within").get<std::size_t>() < first.at("groups").get<std::size_t>());
  CHECK(first.at("worst_group") == "box");
  const auto& last = t.at("steps").back();
  CHECK(last.at("groups_within") == last.at("groups"));
  REQUIRE(t.at("groups").size() == 3);  // floor, wall, box (the light is not counted)
  for (const auto& g : t.at("groups")) {
    INFO(g.dump());
    CHECK(g.at("total").get<double>() <= 0.028);
    CHECK(g.at("total").get<double>() >= std::abs(g.at("estimate").get<double>()));
  }

  // Through the hierarchy (the default route; the form-factor transport, its default) alike; its rays transport
  // holds none by default.
  const Run h = run("solve " + hierarchical + " --json " + json.string());
  INFO(h.out);
  REQUIRE(h.exit_code == 0);
  const nlohmann::json hj = nlohmann::json::parse(file_text(json));
  CHECK(hj.at("target_error").at("each") == "material");
  CHECK(hj.at("target_error").at("steps").size() >= 2);
  CHECK(hj.at("target_error").at("steps").back().at("groups_within").get<std::size_t>() == 3);
  const Run hr = run("solve " + box + " --hierarchical --hierarchical-transport rays --target-error 0.2 --rays 100 " +
                     "--discretisation-directions 2 --json " + json.string());
  INFO(hr.out);
  REQUIRE(hr.exit_code == 0);
  CHECK(nlohmann::json::parse(file_text(json)).at("target_error").at("each") == "none");

  const Run none = run("solve " + scene + " --target-each none --json " + json.string());
  REQUIRE(none.exit_code == 0);
  const nlohmann::json n = nlohmann::json::parse(file_text(json));
  CHECK(n.at("target_error").at("each") == "none");
  CHECK(n.at("target_error").at("steps").size() == 1);
  CHECK_FALSE(n.at("target_error").contains("groups"));

  for (const std::string& bad : {scene + " --target-each colour", hierarchical + " --hierarchical-transport rays --target-each material"}) {
    const Run b = run("solve " + bad);
    INFO(bad << "\n" << b.out);
    CHECK(b.exit_code == 2);
    CHECK(std::count(b.out.begin(), b.out.end(), '\n') == 1);
  }
  const Run needs = run("solve " + source("meshes/cornell_box.obj") + " --target-each material");
  CHECK(needs.exit_code == 2);
}
