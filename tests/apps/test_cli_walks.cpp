// End-to-end: the random-walk options of `radwalk solve` and `radwalk compare`: one-line refusals with the valid
// choices and "did you mean", checked after loading the scene but before any form factor is read or traced, the
// walk counts named apart (--walks-per-patch, --particles), and the warning of a shooting run with too few
// particles.
#include <catch2/catch.hpp>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "radwalk_runner.h"

namespace fs = std::filesystem;

namespace {

// A Matrix Market file that cannot be read: any option check reported instead of its error ran before F.
std::string unreadable_form_factors() {
  const fs::path dir = fs::temp_directory_path() / "radwalk_cli_walks_test";
  fs::create_directories(dir);
  const fs::path path = dir / "broken.mtx";
  std::ofstream(path) << "not a matrix\n";
  return path.string();
}

void check_refused(const std::string& args, const std::string& words) {
  const Run r = run(args);
  INFO("radwalk " << args << " -> exit " << r.exit_code << ": " << r.out);
  CHECK(r.exit_code == 2);
  CHECK(r.out.rfind("radwalk: error: ", 0) == 0);
  CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
  CHECK(r.out.find(words) != std::string::npos);
}

}  // namespace

TEST_CASE("radwalk solve: walk names are refused with the valid choices and the nearest", "[cli][walk]") {
  const std::string rw = "solve " + source("meshes/cube.obj") + " --solver random-walk";
  check_refused(rw + " --estimator colision", "did you mean 'collision'?");
  check_refused(rw + " --estimator survival", "not available for gathering walks");
  check_refused(rw + " --walk shoot --estimator expected-value", "valid: collision, absorption, survival");
  check_refused(rw + " --walk gathr", "did you mean 'gather'?");
  check_refused(rw + " --kernel rey", "did you mean 'ray'?");
  check_refused(rw + " --survival maxx", "did you mean 'max'?");
  check_refused("compare " + source("meshes/cube.obj") + " --estimators gather-collision,shoot-colision",
                "did you mean 'shoot-collision'?");
}

TEST_CASE("radwalk solve: --walks-per-patch counts gathering walks, --particles shooting particles", "[cli][walk]") {
  const std::string rw = "solve " + source("meshes/cube.obj") + " --rays 200 --solver random-walk";
  check_refused(rw + " --walks 100", "use --walks-per-patch for gathering walks or --particles for shooting walks");
  check_refused(rw + " --particles 100", "gathering walks (--walk gather) take --walks-per-patch");
  check_refused(rw + " --walk shoot --walks-per-patch 100", "shooting walks (--walk shoot) take --particles");
  check_refused("compare " + source("meshes/cube.obj") + " --walks 100", "use --walks-per-patch");
  CHECK(run(rw + " --walks-per-patch 100").exit_code == 0);
  CHECK(run(rw + " --walk shoot --particles 1000").exit_code == 0);
}

TEST_CASE("radwalk solve and compare: walk options are checked before the form factors", "[cli][walk]") {
  const std::string cube = source("meshes/cube.obj"), F = " --form-factors " + unreadable_form_factors();
  const std::string rw = "solve " + cube + F + " --solver random-walk";
  check_refused(rw + " --patches 99", "patch 99 is out of range");
  check_refused(rw + " --walks-per-patch 1", "at least 2");
  check_refused(rw + " --survival constant --survival-constant 1", "not in (0, 1)");
  check_refused("compare " + cube + F + " --runs 0", "runs = 0");
  check_refused("compare " + cube + F + " --walks-per-patch 1", "at least 2");
}

TEST_CASE("radwalk solve: a shooting run that leaves most patches at B = 0 says so", "[cli][walk]") {
  // The Cornell box in about 1000 patches from 200 particles: most patches are never reached.
  const std::string rw = "solve " + source("meshes/cornell_box.obj") +
                         " --max-edge 50 --rays 100 --solver random-walk --walk shoot --particles ";
  const Run few = run(rw + "200");
  INFO(few.out);
  CHECK(few.exit_code == 0);
  CHECK(few.out.find("radwalk: warning: shoot-collision: ") != std::string::npos);
  CHECK(few.out.find("use more --particles") != std::string::npos);
  const Run many = run(rw + "200000");
  INFO(many.out);
  CHECK(many.exit_code == 0);
  CHECK(many.out.find("use more --particles") == std::string::npos);
}
