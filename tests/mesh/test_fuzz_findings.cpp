// Regressions of what the fuzz harnesses of tests/fuzz found (docs/reliability.md, section "Fuzzing"), each from
// its reproducer, reduced by hand. The reproducers themselves are in the harnesses' corpora
// (tests/fuzz/corpus/HARNESS/regression-*), which the "fuzz replay" tests run through the oracles.
#include <catch2/catch.hpp>

#include <string>

#include "core/error.h"
#include "mesh/face_geometry.h"
#include "mesh/validate.h"
#include "patch/patching.h"

using namespace radwalk;

TEST_CASE("fuzz finding: a thin quad folded along its length is non-planar", "[mesh][validate][fuzz]") {
  // fuzz_validate_patch (patch areas add up to the face's area): the quad (0,0,0) (1,0,255) (1,1,0) (0,1,0), two
  // halves at nearly 90 degrees, passed validation silently, because its corners are only 1.4e-3 of the long
  // diagonal off their mean plane; its 49 patches added up to 195.1, its area is 180.8. Non-planarity is now
  // measured against the quad's width across its longer diagonal. Reproducer:
  // tests/fuzz/corpus/validate_patch/regression-folded-quad.obj.
  Mesh folded;
  folded.path = "folded";
  folded.vertices = {{0, 0, 0}, {1, 0, 255}, {1, 1, 0}, {0, 1, 0}};
  folded.faces = {{0, 1, 2, 3}};
  Material light;
  light.Ke = Rgb::Ones();
  folded.materials = {light};
  folded.face_material = {0};
  CHECK(quad_nonplanarity(folded, 0) > 0.2);
  CHECK_THROWS_WITH(validate_mesh(folded), Catch::StartsWith("folded: face 0: non-planar quad"));

  // A thin strip (255 x 1) twisted by lifting one corner by 0.35: 1.4e-3 of its diagonal, but 0.35 of its width.
  Mesh twisted = folded;
  twisted.vertices = {{0, 0, 0}, {255, 0, 0}, {255, 1, 0.35}, {0, 1, 0}};
  CHECK_THROWS_WITH(validate_mesh(twisted), Catch::Contains("non-planar quad"));

  // The same strip lifted by 1e-4 of its width stays clean, and its patches add up to its area.
  Mesh flat = folded;
  flat.vertices = {{0, 0, 0}, {255, 0, 0}, {255, 1, 1e-4}, {0, 1, 0}};
  REQUIRE_NOTHROW(validate_mesh(flat));
  const PatchSet patches = make_patches(flat, 255.0 / 7);
  CHECK_THAT(patches.total_area(), Catch::Matchers::WithinRel(face_area(flat, 0), 1e-9));
}
