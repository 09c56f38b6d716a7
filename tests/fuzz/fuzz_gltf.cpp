// Fuzz harness: the glTF reader (mesh/read_gltf.h, read_gltf_bytes), .gltf JSON and .glb.
//
// Input: the bytes of one glTF document, "fuzz/scene.gltf" (a .glb when it starts with the GLB magic). External
// buffers are refused by the harness's resources (an InputError naming the file), so only the document, its
// data: URIs and its BIN chunk are read.
// Contract: read_gltf_bytes returns a Mesh or throws InputError; accessors and views are checked against their
// buffers before any read, the JSON nesting and the triangles made are bounded (libFuzzer's -malloc_limit_mb turns
// a larger allocation into a finding, ASan an out-of-bounds read).
// Oracles:
//   (a) a refusal is one line of printable UTF-8 that starts with a file's path; so is every warning;
//   (reader) an accepted Mesh is what read_gltf.h promises: faces of 3 or 4 corners, each a vertex; materials -1
//       or an index; every material's Kd and Ke finite (the factors are finite numbers).
#include <cmath>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "mesh/read_gltf.h"

using namespace radwalk;
using namespace radwalk::fuzz;

namespace {

const std::string kGltfPath = "fuzz/scene.gltf";

void check_gltf_mesh(const Mesh& mesh) {
  check_read_mesh(mesh);
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    for (int k = 0; k < mesh.corner_count(f); ++k)
      RADWALK_FUZZ_CHECK(static_cast<std::size_t>(mesh.faces[f][static_cast<std::size_t>(k)]) < mesh.vertices.size(),
                         "face " + std::to_string(f) + ": corner out of range");
    RADWALK_FUZZ_CHECK(mesh.face_material[f] < static_cast<std::int32_t>(mesh.materials.size()),
                       "face " + std::to_string(f) + ": material out of range");
  }
  for (const Material& m : mesh.materials)
    RADWALK_FUZZ_CHECK(m.Kd.allFinite() && m.Ke.allFinite(), "material '" + m.name + "': factors not finite");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> files = {kGltfPath};
  GltfResources none{[&files](const std::string& path) -> std::string {
    files.push_back(path);
    throw InputError(path + ": external buffers are not read by the fuzz harness");
  }};
  Mesh mesh;
  if (!accepts([&] { mesh = read_gltf_bytes(kGltfPath, as_text(data, size), none); }, files)) return 0;
  check_gltf_mesh(mesh);
  check_warnings(mesh, {kGltfPath});
  return 0;
}
