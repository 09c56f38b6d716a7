// radwalk's OBJ reader against an independent reference parse of the same files: tinyobjloader. Vertices (to
// tinyobjloader's own parsing error of an ulp or so), faces with their corners in order, and the material name of
// every face must agree on every bundled scene and every well-formed test input.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include <tiny_obj_loader.h>

#include "mesh/read_scene.h"
#include "mesh/text_scan.h"

using namespace radwalk;

namespace {

struct ReferenceFace {
  std::vector<int> corners;
  std::string material;  // "" before any usemtl
};

// The faces of an OBJ in file order as tinyobjloader reads them (shapes in order, faces in order within a shape).
std::vector<ReferenceFace> reference_faces(const std::string& path, tinyobj::attrib_t& attrib) {
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  const std::string dir = directory_of(path);
  REQUIRE(tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, path.c_str(), dir.c_str(), false));
  std::vector<ReferenceFace> faces;
  for (const auto& shape : shapes) {
    std::size_t offset = 0;
    for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      ReferenceFace r;
      for (std::size_t k = 0; k < shape.mesh.num_face_vertices[f]; ++k)
        r.corners.push_back(shape.mesh.indices[offset + k].vertex_index);
      offset += shape.mesh.num_face_vertices[f];
      const int m = f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1;
      r.material = m >= 0 ? materials[static_cast<std::size_t>(m)].name : "";
      faces.push_back(std::move(r));
    }
  }
  return faces;
}

}  // namespace

TEST_CASE("the OBJ reader agrees with tinyobjloader on every bundled and well-formed test scene", "[mesh][read]") {
  const std::string root = RADWALK_SOURCE_DIR;
  for (const std::string file :
       {"meshes/cube.obj", "meshes/furnace.obj", "meshes/cornell_box.obj", "meshes/parallel_squares.obj",
        "meshes/perpendicular_squares.obj", "tests/data/kinds.obj", "tests/data/flipped_face.obj",
        "tests/data/nonmanifold_edge.obj", "tests/data/nonmanifold_vertex.obj", "tests/data/no_material.obj",
        "tests/data/duplicate_face.obj", "tests/data/zero_area.obj", "tests/data/nonplanar_quad.obj"}) {
    INFO(file);
    const std::string path = root + "/" + file;
    const Mesh mesh = read_scene(path);
    tinyobj::attrib_t attrib;
    const std::vector<ReferenceFace> reference = reference_faces(path, attrib);
    REQUIRE(attrib.vertices.size() == 3 * mesh.vertices.size());
    double worst = 0;  // relative vertex difference (tinyobjloader's parser is off by about an ulp)
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
      for (int k = 0; k < 3; ++k) {
        const double x = mesh.vertices[v][k], y = attrib.vertices[3 * v + static_cast<std::size_t>(k)];
        worst = std::max(worst, std::abs(x - y) / std::max(1.0, std::abs(x)));
      }
    CHECK(worst < 1e-14);
    REQUIRE(reference.size() == mesh.face_count());
    for (std::size_t f = 0; f < reference.size(); ++f) {
      INFO("face " << f);
      std::vector<int> corners;
      for (int k = 0; k < mesh.corner_count(f); ++k) corners.push_back(mesh.faces[f][static_cast<std::size_t>(k)]);
      CHECK(corners == reference[f].corners);
      const std::string material =
          mesh.face_material[f] >= 0 ? mesh.materials[static_cast<std::size_t>(mesh.face_material[f])].name : "";
      CHECK(material == reference[f].material);
    }
  }
}
