// Regressions of what the fuzz harnesses of tests/fuzz found (docs/reliability.md, section "Fuzzing"), each
// from its reproducer, reduced by hand. The reproducers themselves are in the harnesses' corpora
// (tests/fuzz/corpus/HARNESS/regression-*), which the "fuzz replay" tests run through the oracles.
#include <catch2/catch.hpp>

#include <string>

#include "core/error.h"
#include "mesh/face_geometry.h"
#include "mesh/mtl.h"
#include "mesh/read_obj.h"
#include "mesh/read_ply.h"
#include "mesh/text_scan.h"
#include "mesh/validate.h"
#include "patch/patching.h"

using namespace radwalk;

namespace {

// An OBJ read from bytes, its one library `mtl` (any name).
Mesh obj_from_text(const std::string& obj, const std::string& mtl) {
  MtlSource libraries{[](const std::string&) { return true; }, [mtl](const std::string&) { return mtl; }};
  return read_obj_text("test.obj", obj, libraries);
}

const std::string kSquare = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

}  // namespace

TEST_CASE("fuzz finding: a thin quad folded along its length is non-planar", "[mesh][validate][fuzz]") {
  // fuzz_validate_patch (patch areas add up to the face's area): the quad (0,0,0) (1,0,255) (1,1,0) (0,1,0),
  // two halves at nearly 90 degrees, passed validation silently, because its corners are only 1.4e-3 of the
  // long diagonal off their mean plane; its 49 patches added up to 195.1, its area is 180.8. Non-planarity is
  // now measured against the quad's width across its longer diagonal. Reproducer:
  // tests/fuzz/corpus/validate_patch/regression-folded-quad.obj.

  // A quad with these corners ("x y z") and an emitting material, read as an OBJ (the face is on line 7).
  auto quad = [](std::initializer_list<const char*> corners) {
    std::string obj = "mtllib m.mtl\nusemtl light\n";
    for (const char* c : corners) obj.append("v ").append(c).append("\n");
    return obj_from_text(obj.append("f 1 2 3 4\n"), "newmtl light\nKe 1 1 1\n");
  };
  Mesh folded = quad({"0 0 0", "1 0 255", "1 1 0", "0 1 0"});
  CHECK(quad_nonplanarity(folded, 0) > 0.2);
  // Refused with --strict; otherwise split into two (planar) triangles, with a warning.
  ValidationTolerances strict;
  strict.strict = true;
  Mesh folded_strict = folded;
  CHECK_THROWS_WITH(validate_mesh(folded_strict, strict), Catch::StartsWith("test.obj:7: face 0: non-planar quad"));
  Mesh folded_split = folded;
  REQUIRE_NOTHROW(validate_mesh(folded_split));
  CHECK(folded_split.face_count() == 2);

  // A thin strip (255 x 1) twisted by lifting one corner by 0.35: 1.4e-3 of its diagonal, but 0.35 of its width.
  Mesh twisted = quad({"0 0 0", "255 0 0", "255 1 0.35", "0 1 0"});
  CHECK_THROWS_WITH(validate_mesh(twisted, strict), Catch::Contains("non-planar quad"));
  REQUIRE_NOTHROW(validate_mesh(twisted));
  CHECK(twisted.face_count() == 2);

  // The same strip lifted by 1e-4 of its width stays clean, and its patches add up to its area.
  Mesh flat = quad({"0 0 0", "255 0 0", "255 1 1e-4", "0 1 0"});
  REQUIRE_NOTHROW(validate_mesh(flat));
  const PatchSet patches = make_patches(flat, 255.0 / 7);
  CHECK_THAT(patches.total_area(), Catch::Matchers::WithinRel(face_area(flat, 0), 1e-9));
}

TEST_CASE("fuzz finding: '+' followed by another sign is not a number", "[mesh][read][fuzz]") {
  // fuzz_mtl (number rule vs strtod): "Kd +-.5 .25 5." was read as Kd -0.5: the '+' was removed and
  // from_chars read the rest, sign and all. Likewise "f +-1 ..." was the relative index -1. Reproducer:
  // tests/fuzz/corpus/mtl/regression-plus-minus.mtl.
  CHECK(parse_number("+-.5").status == NumberStatus::not_a_number);
  CHECK(parse_number("++5").status == NumberStatus::not_a_number);
  CHECK(!parse_long("+-3"));
  CHECK(parse_number("+.5").value == 0.5);
  CHECK(parse_long("+3") == 3);
  CHECK_THROWS_WITH(scan_mtl_text("test.mtl", "newmtl a\nKd +-.5 .25 5.\n"),
                    Catch::StartsWith("test.mtl:2: Kd: '+-.5' is not a number"));
  // Collected as error findings (the rest of the file is still read), refused by validation.
  auto first_error = [](const Mesh& mesh) {
    for (const Finding& f : mesh.findings)
      if (f.severity == Severity::error) return f.message;
    return std::string();
  };
  CHECK_THAT(first_error(obj_from_text("v +-1 0 0\n", "")), Catch::Contains("'+-1' is not a number"));
  CHECK_THAT(first_error(obj_from_text(kSquare + "f 1 2 +-1\n", "")), Catch::Contains("'+-1' is not a vertex index"));
}

TEST_CASE("fuzz finding: underflow and overflow are told apart by the value, not by the sign of the exponent",
          "[mesh][read][fuzz]") {
  // Found reading parse_number while writing fuzz_mtl's number oracle, confirmed by it (the fuzzer itself did
  // not reach 400-digit numbers in a few minutes): a 1 with 400 zeros and "e-10" (1e390) was read as 0, and
  // 1e-401 written without an exponent was "out of range". Reproducers:
  // tests/fuzz/corpus/mtl/regression-*-digits.mtl.
  const std::string zeros(400, '0');
  // (written with append: GCC 12 warns falsely (-Wrestrict) about "literal" + std::string)
  auto number = [](std::string a, const std::string& b, const std::string& c) {
    return a.append(b).append(c);
  };
  CHECK(parse_number(number("1", zeros, "e-10")).status == NumberStatus::out_of_range);
  CHECK(parse_number(number("-1", zeros, ".5e-10")).status == NumberStatus::out_of_range);
  const ParsedNumber tiny = parse_number(number("0.", zeros, "1"));
  CHECK(tiny.status == NumberStatus::ok);
  CHECK(tiny.value == 0.0);
  CHECK(parse_number(number("0.", zeros, "1e100")).value == 1e-301);
  CHECK(parse_number("0.0001e-400").value == 0.0);
  CHECK(parse_number(number("1", zeros.substr(0, 300), "e-10")).value == 1e290);
}

TEST_CASE("fuzz finding: MTL numbers must be finite, Pr in [0, 1]", "[mesh][read][mtl][fuzz]") {
  // fuzz_mtl: "Ks 0.5 inf 0.5" and "Ni nan" were accepted (validation checks only Kd and Ke, and only of used
  // materials), and "Pr 0.51e308" gave the roughness Pr^2 = inf. Reproducers:
  // tests/fuzz/corpus/mtl/regression-inf-accepted.mtl, regression-pr-overflow.mtl.
  CHECK_THROWS_WITH(scan_mtl_text("test.mtl", "newmtl m\nKs 0.5 inf 0.5\n"),
                    Catch::StartsWith("test.mtl:2: Ks: 'inf' is not a finite number"));
  CHECK_THROWS_WITH(scan_mtl_text("test.mtl", "newmtl m\nNi nan\n"),
                    Catch::Contains("'nan' is not a finite number"));
  CHECK_THROWS_WITH(scan_mtl_text("test.mtl", "newmtl m\nKd -inf\n"), Catch::Contains("not a finite number"));
  CHECK_THROWS_WITH(scan_mtl_text("test.mtl", "newmtl m\nKe 1e999 0 0\n"),
                    Catch::Contains("'1e999' is out of range"));
  CHECK_THROWS_WITH(scan_mtl_text("test.mtl", "newmtl m\nPr 0.51e308\n"),
                    Catch::StartsWith("test.mtl:2: Pr (roughness) must be in [0, 1]"));
  CHECK_THROWS_WITH(scan_mtl_text("test.mtl", "newmtl m\nPr -0.5\n"), Catch::Contains("must be in [0, 1]"));
  const auto entries = scan_mtl_text("test.mtl", "newmtl m\nPr 1\nillum 3\n");
  REQUIRE(entries.size() == 1);
  CHECK(material_from_mtl(entries[0]).roughness == 1.0);
}

TEST_CASE("fuzz finding: an ascii PLY index or list length of 1e30 is reported, not cast",
          "[mesh][ply][fuzz]") {
  // fuzz_ply (UBSan): the message for an out-of-range vertex index cast the double 7.8e27 to long long
  // (undefined behaviour), as did the one for a list length past the end of the file. Reproducer:
  // tests/fuzz/corpus/ply/regression-huge-index.ply.
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n";
  // A bad index is a finding of the face (all of them are collected; validation refuses the scene).
  auto refused = [](const std::string& bytes) {
    Mesh mesh = read_ply_bytes("test.ply", bytes);
    validate_mesh(mesh);
  };
  CHECK_THROWS_WITH(refused(head + "3 0 1 7.8e27\n"),
                    Catch::StartsWith("test.ply:13: face 0: vertex index 7.8e+27 is out of range (3 vertices)"));
  CHECK_THROWS_WITH(read_ply_bytes("test.ply", head + "1e30 0 1 2\n"),
                    Catch::Contains("list length 1e+30 runs past the end of the file"));
  CHECK_THROWS_WITH(refused(head + "3 0 1 -2\n"), Catch::Contains("vertex index -2 is out of range"));
}

TEST_CASE("fuzz finding: an emission whose E = pi Ke overflows is refused", "[mesh][validate][fuzz]") {
  // fuzz_validate_patch (materials physical and finite after validation): Ke 1e308 is finite, E = pi Ke is not.
  // Reproducer: tests/fuzz/corpus/validate_patch/regression-huge-emission.obj.
  Mesh mesh;
  mesh.path = "huge";
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  mesh.faces = {{0, 1, 2, 3}};
  Material light;
  light.name = "light";
  light.Ke = Rgb(1e308, 0, 0);
  mesh.materials = {light};
  mesh.face_material = {0};
  CHECK_THROWS_WITH(validate_mesh(mesh), Catch::StartsWith("huge: face 0: emission too large"));
  mesh.materials[0].Ke = Rgb(1e300, 0, 0);
  CHECK_NOTHROW(validate_mesh(mesh));
}
