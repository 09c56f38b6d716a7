// The PLY reader: exact doubles, both byte orders, colours in range, bounded element counts, one-line refusals,
// and OpenMesh as the independent reference parse of the bundled PLY.
#include <catch2/catch.hpp>

#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include "core/error.h"
#include "mesh/read_ply.h"
#include "mesh/read_scene.h"
#include "mesh/validate.h"

using namespace radwalk;
namespace fs = std::filesystem;

namespace {

const std::string kPlyPath = "test.ply";

// Appends the bytes of x in the given byte order.
template <class T>
void put(std::string& out, T x, bool big_endian) {
  char b[sizeof(T)];
  std::memcpy(b, &x, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big)) std::reverse(b, b + sizeof(T));
  out.append(b, sizeof(T));
}

// A unit square (one quad) with double coordinates offset by a UTM-sized easting, and a ushort colour.
std::string binary_square(bool big_endian, double easting, std::uint16_t red) {
  std::string s = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
                  "element face 1\nproperty list uchar uint vertex_indices\nproperty ushort red\n"
                  "property ushort green\nproperty ushort blue\nend_header\n";
  const double xy[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (const auto& p : xy) {
    put(s, easting + p[0] * 0.01, big_endian);
    put(s, 5e6 + p[1] * 0.01, big_endian);
    put(s, 0.0, big_endian);
  }
  put(s, std::uint8_t{4}, big_endian);
  for (std::uint32_t v = 0; v < 4; ++v) put(s, v, big_endian);
  put(s, red, big_endian);
  put(s, std::uint16_t{10}, big_endian);
  put(s, std::uint16_t{20}, big_endian);
  return s;
}

// Read and validate (a face's own defects are findings; validation refuses the scene with all of them).
Mesh load_ply_bytes(const std::string& bytes) {
  Mesh mesh = read_ply_bytes(kPlyPath, bytes);
  validate_mesh(mesh);
  return mesh;
}

}  // namespace

TEST_CASE("PLY double coordinates stay doubles, in either byte order", "[mesh][ply]") {
  // W6: UTM-sized coordinates read in single precision lost centimetres.
  for (bool big : {false, true}) {
    INFO((big ? "big" : "little") << " endian");
    const Mesh mesh = read_ply_bytes(kPlyPath, binary_square(big, 654321.0, 200));
    REQUIRE(mesh.vertices.size() == 4);
    CHECK(mesh.vertices[1].x() == 654321.0 + 0.01);
    CHECK(mesh.vertices[2].y() == 5e6 + 0.01);
    REQUIRE(mesh.face_count() == 1);
    CHECK(mesh.is_quad(0));
    CHECK(mesh.face_line[0] == 0);  // binary: no lines
    CHECK(mesh.materials[static_cast<std::size_t>(mesh.face_material[0])].Kd[0] == 200.0 / 255.0);
  }
}

TEST_CASE("PLY colours outside 0..255 are refused, not wrapped", "[mesh][ply]") {
  // W7: 300 wrapped to 44.
  CHECK_THROWS_WITH(load_ply_bytes(binary_square(false, 0, 300)),
                    Catch::Contains("test.ply") && Catch::Contains("face 0") && Catch::Contains("outside 0..255"));
  const std::string floats =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 2\nproperty list uchar int vertex_indices\nproperty float red\nproperty float green\n"
      "property float blue\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 0.5 0.25 1\n3 0 2 1 1.5 0 0\n";
  CHECK_THROWS_WITH(load_ply_bytes(floats), Catch::Contains("test.ply:17") && Catch::Contains("outside 0..1"));
  const std::string ok = floats.substr(0, floats.rfind("3 0 2 1")) + "3 0 2 1 0.5 0.25 1\n";
  const Mesh mesh = read_ply_bytes(kPlyPath, ok);
  CHECK(mesh.materials.size() == 1);
  CHECK(mesh.materials[0].Kd[1] == 0.25);
}

TEST_CASE("PLY per-face defects are all reported at once, each naming its face and line", "[mesh][ply]") {
  // The PLY reader collects every bad face before it refuses, as the OBJ reader does.
  const std::string text =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 6\nproperty list uchar int vertex_indices\nproperty uchar red\nproperty uchar green\n"
      "property uchar blue\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
      "3 0 1 7 10 10 10\n"     // face 0 (line 16): bad index
      "3 0 1 2 300 10 10\n"    // face 1: colour out of range
      "2 0 1 10 10 10\n"       // face 2: two corners
      "3 0 1 2 10 10 10\n"     // face 3: fine
      "3 9 8 2 10 10 10\n"     // face 4: two bad indices, one finding
      "3 0 1 5 999 10 10\n";   // face 5: bad index and colour
  const Mesh read = read_ply_bytes(kPlyPath, text);
  CHECK(read.face_count() == 1);  // only face 3 is kept
  struct Expected {
    long face, line;
    std::string kind;
  };
  const std::vector<Expected> expected = {{0, 16, "bad vertex index"}, {1, 17, "colour out of range"},
                                          {2, 18, "face of fewer than 3 corners"}, {4, 20, "bad vertex index"},
                                          {5, 21, "bad vertex index"}, {5, 21, "colour out of range"}};
  REQUIRE(read.findings.size() == expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) {
    INFO(finding_line(read.findings[k]));
    CHECK(read.findings[k].face == expected[k].face);
    CHECK(read.findings[k].line == expected[k].line);
    CHECK(read.findings[k].kind == expected[k].kind);
    CHECK(read.findings[k].severity == Severity::error);
  }
  try {
    (void)load_ply_bytes(text);
    FAIL("not refused");
  } catch (const MeshRefused& e) {
    std::size_t errors = 0;
    for (const Finding& f : e.findings()) errors += f.severity == Severity::error;
    CHECK(errors == expected.size());
    CHECK(std::string(e.what()).find("; and 5 more: 6 errors") != std::string::npos);
  }
  // Binary: the bad face's values are still read, so the next face is read right.
  std::string bin = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";
  for (float c : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) put(bin, c, false);
  put(bin, std::uint8_t{3}, false);
  for (std::int32_t v : {0, 1, 9}) put(bin, v, false);
  put(bin, std::uint8_t{3}, false);
  for (std::int32_t v : {0, 1, 2}) put(bin, v, false);
  const Mesh b = read_ply_bytes(kPlyPath, bin);
  CHECK(b.face_count() == 1);
  std::vector<Finding> errors;
  for (const Finding& f : b.findings)
    if (f.severity == Severity::error) errors.push_back(f);
  REQUIRE(errors.size() == 1);
  CHECK(errors[0].face == 0);
  CHECK(b.faces[0][2] == 2);
}

TEST_CASE("PLY element counts are bounded by the bytes of the file", "[mesh][ply]") {
  // O2: a 196-byte file declaring 4e9 vertices ran out of memory.
  const std::string huge =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  CHECK_THROWS_WITH(read_ply_bytes(kPlyPath, huge),
                    Catch::Contains("test.ply:3") && Catch::Contains("4000000000") && Catch::Contains("bytes follow"));
  const std::string ascii_huge =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 99999999999\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n";
  CHECK_THROWS_WITH(read_ply_bytes(kPlyPath, ascii_huge), Catch::Contains("99999999999"));
  // A list length that runs past the end of the file.
  std::string list = "ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
                     "property float z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n";
  put(list, std::uint32_t{4000000000u}, false);
  CHECK_THROWS_WITH(read_ply_bytes(kPlyPath, list), Catch::Contains("runs past the end"));
}

TEST_CASE("PLY refusals name the real cause on one line", "[mesh][ply]") {
  // P5: a malformed header gave "1The ..." from OpenMesh.
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n";
  struct Case {
    std::string text, expected;
  };
  for (const Case& c :
       {Case{"plx\n", "not a PLY file"}, Case{head + "property float z\nend_header\n", "no face element"},
        Case{head + "property flot z\n", "test.ply:6: malformed property"},
        Case{head + "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                    "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n",
             "test.ply:13: face 0: vertex index 7 is out of range"},
        Case{head + "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                    "0 0 0\n1 0 x\n",
             "test.ply:11: vertex 2 z: 'x' is not a number"},
        Case{head + "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                    "0 0 0\n1 0 0\n",
             "file ends before vertex 3"},
        Case{head + "property float z\nelement face 1\nproperty list uchar int vertex_indices\n", "no end_header"}}) {
    INFO(c.text);
    try {
      (void)load_ply_bytes(c.text);
      FAIL("no error");
    } catch (const InputError& e) {
      const std::string what = e.what();
      INFO(what);
      CHECK(what.find('\n') == std::string::npos);
      CHECK(what.find(c.expected) != std::string::npos);
    }
  }
}

TEST_CASE("the PLY reader agrees with OpenMesh on the bundled PLY scene", "[mesh][ply]") {
  using PlyMesh = OpenMesh::PolyMesh_ArrayKernelT<>;
  const std::string path = std::string(RADWALK_SOURCE_DIR) + "/meshes/cube.ply";
  PlyMesh om;
  om.request_face_colors();
  OpenMesh::IO::Options options = OpenMesh::IO::Options::FaceColor;
  REQUIRE(OpenMesh::IO::read_mesh(om, path, options));
  const Mesh mesh = read_scene(path);
  REQUIRE(mesh.vertices.size() == om.n_vertices());
  REQUIRE(mesh.face_count() == om.n_faces());
  for (const auto vh : om.vertices())
    for (int k = 0; k < 3; ++k) CHECK(mesh.vertices[static_cast<std::size_t>(vh.idx())][k] == om.point(vh)[k]);
  for (const auto fh : om.faces()) {
    const auto f = static_cast<std::size_t>(fh.idx());
    int k = 0;
    for (const auto vh : om.fv_range(fh)) CHECK(mesh.faces[f][static_cast<std::size_t>(k++)] == vh.idx());
    CHECK(k == mesh.corner_count(f));
    const auto c = om.color(fh);
    const Rgb rho = mesh.materials[static_cast<std::size_t>(mesh.face_material[f])].Kd;
    for (int ch = 0; ch < 3; ++ch) CHECK(rho[ch] == c[ch] / 255.0);
  }
}
