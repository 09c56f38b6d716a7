// The STL, glTF/GLB and VTK readers (mesh/read_stl.h, read_gltf.h, read_vtk.h) against the OBJ reader on one
// scene written in every format (tests/support/scene_formats.h: float-exact coordinates), their transforms and
// materials, and their one-line refusals of malformed files.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <string>

#include "core/error.h"
#include "mesh/face_geometry.h"
#include "mesh/material_override.h"
#include "mesh/read_gltf.h"
#include "mesh/read_obj.h"
#include "mesh/read_scene.h"
#include "mesh/read_stl.h"
#include "mesh/read_vtk.h"
#include "mesh/validate.h"
#include "support/scene_formats.h"

using namespace radwalk;
namespace fs = std::filesystem;

namespace {

fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / ("radwalk_formats_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

// The corner positions of face f.
std::vector<Vec3> corners(const Mesh& m, std::size_t f) {
  std::vector<Vec3> out;
  for (int k = 0; k < m.corner_count(f); ++k) out.push_back(m.vertices[static_cast<std::size_t>(m.faces[f][k])]);
  return out;
}

// Same faces (corner positions, in order), same areas exactly, and the same reflectance and emission per face.
void require_same_faces(const Mesh& a, const Mesh& b, bool compare_materials) {
  REQUIRE(a.face_count() == b.face_count());
  for (std::size_t f = 0; f < a.face_count(); ++f) {
    INFO("face " << f);
    REQUIRE(corners(a, f) == corners(b, f));
    REQUIRE(face_area(a, f) == face_area(b, f));
    if (!compare_materials) continue;
    const Material& ma = a.materials[static_cast<std::size_t>(a.face_material[f])];
    const Material& mb = b.materials[static_cast<std::size_t>(b.face_material[f])];
    REQUIRE(ma.Kd.isApprox(mb.Kd, 0));
    REQUIRE((ma.Ke == mb.Ke).all());
  }
}

// `body` throws InputError whose message is one line starting with `path` and containing `words`.
template <class Body>
void require_one_line_refusal(Body&& body, const std::string& path, const std::string& words) {
  try {
    body();
    FAIL("accepted; expected a refusal with '" << words << "'");
  } catch (const InputError& e) {
    const std::string m = e.what();
    INFO(m);
    REQUIRE(m.rfind(path, 0) == 0);
    REQUIRE(m.find('\n') == std::string::npos);
    REQUIRE(m.find(words) != std::string::npos);
  }
}

}  // namespace

TEST_CASE("STL (ascii, binary) and glTF (.gltf, .glb) give the OBJ's faces, areas and materials", "[mesh][formats]") {
  const fs::path dir = scratch();
  const test::TriScene scene = test::box_with_panel();
  test::write_all_formats(scene, dir);
  Mesh obj = load_scene((dir / "scene.obj").string());
  REQUIRE(obj.face_count() == 14);

  SECTION("ascii STL: one group and material per solid, named by the solid; --set gives the materials") {
    Mesh stl = read_scene((dir / "scene_ascii.stl").string());
    REQUIRE(stl.groups.size() == 4);
    REQUIRE(stl.group_name[0] == "white");
    std::vector<MaterialOverride> sets;
    for (const auto& [name, c] : scene.materials) {
      sets.push_back(parse_material_override(name + ".Kd=" + test::number(c.kd[0]) + "," + test::number(c.kd[1]) +
                                             "," + test::number(c.kd[2])));
      sets.push_back(parse_material_override(name + ".Ke=" + test::number(c.ke[0]) + "," + test::number(c.ke[1]) +
                                             "," + test::number(c.ke[2])));
    }
    apply_material_overrides(stl, sets);
    validate_mesh(stl);
    require_same_faces(obj, stl, true);
  }
  SECTION("binary STL: one group named by the file's stem; the same faces") {
    Mesh stl = read_scene((dir / "scene_binary.stl").string());
    REQUIRE(stl.group_name == std::vector<std::string>{"scene_binary"});
    apply_material_overrides(stl, {parse_material_override("scene_binary.Kd=0.5")});
    validate_mesh(stl);
    require_same_faces(obj, stl, false);
  }
  SECTION(".gltf with an external buffer and .glb: node transforms applied, materials from the factors") {
    for (const char* file : {"scene.gltf", "scene.glb"}) {
      INFO(file);
      Mesh gltf = load_scene((dir / file).string());
      require_same_faces(obj, gltf, true);
      REQUIRE(gltf.group_object[0] == "node_white");
      REQUIRE(gltf.group_name[0] == "white");
    }
  }
  fs::remove_all(dir);
}

TEST_CASE("STL without --set is refused naming --set, and unknown formats list the known ones", "[mesh][formats]") {
  const fs::path dir = scratch();
  const std::string stl = test::write_file(dir / "s.stl", test::ascii_stl(test::box_with_panel())).string();
  require_one_line_refusal([&] { load_scene(stl); }, stl, "--set 'white.Kd=r,g,b'");
  const std::string dae = test::write_file(dir / "s.dae", "<COLLADA/>").string();
  require_one_line_refusal([&] { load_scene(dae); }, dae, "assimp export");
  const std::string xyz = test::write_file(dir / "s.xyz", "1 2 3").string();
  require_one_line_refusal([&] { load_scene(xyz); }, xyz, ".stl, .gltf, .glb, .vtp and .vtk");
  fs::remove_all(dir);
}

TEST_CASE("glTF: scale, rotation and mirror transforms, strips and fans, doubleSided and defaults", "[mesh][formats]") {
  // One triangle (0,0,0) (1,0,0) (0,1,0) facing +z, used by three nodes.
  std::string bin;
  for (double v : {0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0}) test::put_f32(bin, v);
  auto doc = [&](const std::string& nodes, const std::string& mode, const std::string& material) {
    return "{\"asset\":{\"version\":\"2.0\"},\"nodes\":[" + nodes +
           "],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}" + mode +
           ",\"material\":0}]}],\"materials\":[" + material +
           "],\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}],"
           "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],\"buffers\":[{\"byteLength\":36}]}";
  };
  const std::string plain = "{\"name\":\"m\"}";
  SECTION("a parent's scale and a child's translation compose; a mirror reverses the corner order") {
    const std::string nodes = "{\"name\":\"parent\",\"scale\":[2,2,2],\"children\":[1,2]},"
                              "{\"name\":\"child\",\"mesh\":0,\"translation\":[0,0,1]},"
                              "{\"name\":\"mirror\",\"mesh\":0,\"scale\":[1,1,-1]}";
    const Mesh m = read_gltf_bytes("t.glb", test::glb(doc(nodes, "", plain), bin), {});
    REQUIRE(m.face_count() == 2);
    REQUIRE(corners(m, 0) == std::vector<Vec3>{Vec3(0, 0, 2), Vec3(2, 0, 2), Vec3(0, 2, 2)});
    REQUIRE(face_vector_area(m, 0).normalized().isApprox(Vec3(0, 0, 1)));
    // Mirrored in z: the triangle lies in z = 0 still, its corners reversed so that it faces -z as the mirror does.
    REQUIRE(face_vector_area(m, 1).normalized().isApprox(Vec3(0, 0, -1)));
    REQUIRE(m.group_object[0] == "child");
    REQUIRE(m.group_name[0] == "mesh_0");
  }
  SECTION("a rotation by 90 degrees about x takes the +z normal to -y") {
    const double h = std::sqrt(0.5);
    const std::string nodes = "{\"mesh\":0,\"rotation\":[" + test::number(h) + ",0,0," + test::number(h) + "]}";
    const Mesh m = read_gltf_bytes("t.glb", test::glb(doc(nodes, "", plain), bin), {});
    REQUIRE(face_vector_area(m, 0).normalized().isApprox(Vec3(0, -1, 0)));
  }
  SECTION("strip and fan of 3 vertices are one triangle each, facing as the list") {
    for (const char* mode : {",\"mode\":5", ",\"mode\":6"}) {
      const Mesh m = read_gltf_bytes("t.glb", test::glb(doc("{\"mesh\":0}", mode, plain), bin), {});
      REQUIRE(m.face_count() == 1);
      REQUIRE(face_vector_area(m, 0).normalized().isApprox(Vec3(0, 0, 1)));
    }
  }
  SECTION("materials: base colour as rho, emissive x strength as Ke, doubleSided as two-sided, default white") {
    const std::string material =
        "{\"name\":\"lamp\",\"doubleSided\":true,\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.25,0.5,0.75,1]},"
        "\"emissiveFactor\":[1,0.5,0],\"extensions\":{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":8}}}";
    const Mesh m = read_gltf_bytes("t.glb", test::glb(doc("{\"mesh\":0}", "", material), bin), {});
    REQUIRE(m.materials[0].name == "lamp");
    REQUIRE((m.materials[0].Kd == Rgb(0.25, 0.5, 0.75)).all());
    REQUIRE((m.materials[0].Ke == Rgb(8, 4, 0)).all());
    REQUIRE(m.materials[0].two_sided);
    const Mesh d = read_gltf_bytes("t.glb", test::glb(doc("{\"mesh\":0}", "", "{}"), bin), {});
    REQUIRE(d.materials[0].name == "material_0");
    REQUIRE((d.materials[0].Kd == 1).all());  // glTF's default base colour: validation refuses rho = 1
  }
}

TEST_CASE("malformed STL, glTF and GLB files are refused in one line naming the file", "[mesh][formats]") {
  const test::TriScene scene = test::box_with_panel();
  const std::string binary = test::binary_stl(scene);
  require_one_line_refusal([&] { read_stl_bytes("b.stl", binary.substr(0, binary.size() - 7)); }, "b.stl",
                           "binary STL declares 14 triangles");
  std::string huge = binary.substr(0, 84);
  huge[80] = huge[81] = huge[82] = huge[83] = '\xff';  // 4e9 triangles in 84 bytes: refused before allocating
  require_one_line_refusal([&] { read_stl_bytes("h.stl", huge); }, "h.stl", "4294967295 triangles");
  const std::string ascii = test::ascii_stl(scene);
  require_one_line_refusal([&] { read_stl_bytes("a.stl", ascii.substr(0, ascii.find("  facet", ascii.size() / 2))); }, "a.stl",
                           "file ends inside solid");
  require_one_line_refusal([&] { read_stl_bytes("v.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 1 2\n"); },
                           "v.stl", "expected 'vertex x y z'");
  require_one_line_refusal([&] { read_stl_bytes("n.stl", "hello"); }, "n.stl", "not an STL file");

  const auto [json, bin] = test::gltf(scene, "");
  const std::string good = test::glb(json, bin);
  REQUIRE_NOTHROW(read_gltf_bytes("g.glb", good, {}));
  require_one_line_refusal([&] { read_gltf_bytes("g.glb", good.substr(0, good.size() - 4), {}); }, "g.glb",
                           "GLB header: declares");
  require_one_line_refusal([&] { read_gltf_bytes("j.gltf", "{\"asset\":{\"version\":\"2.0\"},", {}); }, "j.gltf",
                           "not valid JSON");
  require_one_line_refusal([&] { read_gltf_bytes("j.gltf", std::string(100, '[') + std::string(100, ']'), {}); },
                           "j.gltf", "nested more than 64 deep");
  require_one_line_refusal([&] { read_gltf_bytes("v.gltf", "{\"asset\":{\"version\":\"1.0\"}}", {}); }, "v.gltf",
                           "radwalk reads glTF 2.x");
  // An accessor that runs past its buffer view.
  std::string long_accessor = json;
  const std::size_t count = long_accessor.find("\"count\":");
  long_accessor.replace(count, 8, "\"count\":9999");
  require_one_line_refusal([&] { read_gltf_bytes("c.glb", test::glb(long_accessor, bin), {}); }, "c.glb",
                           "do not fit");
  // A node that is its own child.
  const std::string cycle = "{\"asset\":{\"version\":\"2.0\"},\"nodes\":[{\"children\":[1]},{\"children\":[1]}]}";
  require_one_line_refusal([&] { read_gltf_bytes("n.gltf", cycle, {}); }, "n.gltf", "reached twice");
  // A required extension radwalk does not read.
  require_one_line_refusal(
      [&] { read_gltf_bytes("d.gltf", "{\"asset\":{\"version\":\"2.0\"},\"extensionsRequired\":[\"KHR_draco_mesh_compression\"]}", {}); },
      "d.gltf", "KHR_draco_mesh_compression");
  // A missing external buffer.
  require_one_line_refusal([&] { read_gltf_bytes("/nonexistent/x.gltf", test::gltf(scene, "x.bin").first, gltf_files_on_disk()); },
                           "/nonexistent/x.bin", "");
}

TEST_CASE("VTK legacy and XML polydata: polygons, strips, rho and E fields, and bad counts refused", "[mesh][formats]") {
  const std::string legacy =
      "# vtk DataFile Version 3.0\nsquare\nASCII\nDATASET POLYDATA\nPOINTS 5 double\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
      "0.5 0 0\nPOLYGONS 1 6\n5 0 4 1 2 3\nCELL_DATA 1\nSCALARS rho double 3\nLOOKUP_TABLE default\n0.5 0.25 0.125\n";
  const Mesh m = read_vtk_polydata_bytes("s.vtk", legacy, false);
  REQUIRE(m.face_count() == 1);
  REQUIRE(m.is_quad(0));  // the point on the edge (a T-junction point) is dropped
  REQUIRE((m.materials[0].Kd == Rgb(0.5, 0.25, 0.125)).all());
  REQUIRE_FALSE(m.materials[0].reflectance_missing);

  const std::string no_rho = "# vtk DataFile Version 3.0\nsquare\nASCII\nDATASET POLYDATA\nPOINTS 4 float\n"
                             "0 0 0\n1 0 0\n1 1 0\n0 1 0\nTRIANGLE_STRIPS 1 5\n4 0 1 3 2\n";
  Mesh strip = read_vtk_polydata_bytes("plain.vtk", no_rho, false);
  REQUIRE(strip.face_count() == 2);
  REQUIRE(face_vector_area(strip, 0).normalized().isApprox(Vec3(0, 0, 1)));
  REQUIRE(face_vector_area(strip, 1).normalized().isApprox(Vec3(0, 0, 1)));
  REQUIRE(strip.materials[0].name == "plain");
  REQUIRE(strip.materials[0].reflectance_missing);

  require_one_line_refusal(
      [&] {
        read_vtk_polydata_bytes("big.vtk",
                                "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 4000000000 float\n",
                                false);
      },
      "big.vtk", "more than its");
  // Found by the vtk fuzz harness: a word among a polygon's indices made VTK 9.1's legacy reader read the stream it
  // had closed (a segmentation fault); now refused naming the line. So are a short section and a bad point.
  const std::string head = "# vtk DataFile Version 3.0\nsquare\nASCII\nDATASET POLYDATA\nPOINTS 4 double\n";
  require_one_line_refusal(
      [&] { read_vtk_polydata_bytes("word.vtk", head + "0 0 0\n1 0 0\n1 1 0\n0 1 0\nPOLYGONS 1 5\nfloat 0 1 2 3\n", false); },
      "word.vtk:11:", "POLYGONS (line 10): 'float' is not a whole number from 0 to 2147483647");
  // Found by the vtk fuzz harness: VTK 9.1 reads legacy cell sections as 32-bit ints; 2^31 made it crash.
  require_one_line_refusal(
      [&] { read_vtk_polydata_bytes("wide.vtk", head + "0 0 0\n1 0 0\n1 1 0\n0 1 0\nPOLYGONS 1 5\n4 0 1 2 2147483648\n", false); },
      "wide.vtk:11:", "POLYGONS (line 10): '2147483648' is not a whole number from 0 to 2147483647");
  require_one_line_refusal(
      [&] { read_vtk_polydata_bytes("short.vtk", head + "0 0 0\n1 0 0\n1 1 0\n0 1 0\nPOLYGONS 1 5\n4 0 1 2\n", false); },
      "short.vtk:10:", "POLYGONS ends before its 5 indices");
  require_one_line_refusal(
      [&] { read_vtk_polydata_bytes("point.vtk", head + "0 0 0\n1 0 x\n1 1 0\n0 1 0\nPOLYGONS 1 5\n4 0 1 2 3\n", false); },
      "point.vtk:7:", "POINTS (line 5): 'x' is not a number");
  // Found by the vtk fuzz harness: VTK matches the POINTS type by its prefix, and "stringdouble" made its legacy
  // reader read string points and dereference a null pointer; only VTK's numeric type names are taken.
  require_one_line_refusal(
      [&] {
        read_vtk_polydata_bytes("string.vtk", "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\n"
                                              "POINTS 3 stringdouble\n0 0 0 1 0 0 0 1 0\nPOLYGONS 1 4\n3 0 1 2\n", false);
      },
      "string.vtk:5:", "POINTS of type 'stringdouble': not one of VTK's numeric types");
  // Found by the vtk fuzz harness: an array type VTK does not know (a radwalk .vtp with "Int64" mutated to "Int28")
  // crashed VTK 9.1's XML reader; now refused naming the type.
  require_one_line_refusal(
      [&] {
        read_vtk_polydata_bytes("type.vtp",
                                "<VTKFile type=\"PolyData\"><PolyData><FieldData><DataArray type=\"Int28\" "
                                "Name=\"patches\" NumberOfTuples=\"1\" format=\"ascii\">1</DataArray></FieldData>"
                                "</PolyData></VTKFile>",
                                true);
      },
      "type.vtp", "DataArray of type \"Int28\": not one of Int8");
  // The version 5.1 layout (OFFSETS and CONNECTIVITY sections) is read as before.
  const Mesh v51 = read_vtk_polydata_bytes(
      "v51.vtk",
      "# vtk DataFile Version 5.1\nsquare\nASCII\nDATASET POLYDATA\nPOINTS 4 float\n0 0 0 1 0 0 1 1 0 0 1 0\n"
      "POLYGONS 2 4\nOFFSETS vtktypeint64\n0 4\nCONNECTIVITY vtktypeint64\n0 1 2 3\n",
      false);
  REQUIRE(v51.face_count() == 1);
  require_one_line_refusal([&] { read_vtk_polydata_bytes("bad.vtp", "<VTKFile type=\"PolyData\"><Poly", true); },
                           "bad.vtp", "not well-formed XML");
  require_one_line_refusal(
      [&] {
        read_vtk_polydata_bytes("big.vtp",
                                "<VTKFile type=\"PolyData\"><PolyData><Piece NumberOfPoints=\"900000000\" "
                                "NumberOfPolys=\"1\"></Piece></PolyData></VTKFile>",
                                true);
      },
      "big.vtp", "more than its");
}
