// Fuzz harness: the STL reader (mesh/read_stl.h, read_stl_bytes), ascii and binary.
//
// Input: the bytes of one STL file, "fuzz/scene.stl".
// Contract: read_stl_bytes returns a Mesh or throws InputError; a binary file allocates only after its count
// matched its size (libFuzzer's -malloc_limit_mb turns a larger allocation into a finding).
// Oracles:
//   (a) a refusal is one line of printable UTF-8 that starts with the file's path; so is every warning;
//   (reader) an accepted Mesh is what read_stl.h promises: finite-or-kept vertices, faces of 3 or 4 corners,
//       each a vertex of the file; one group per solid and one material per group, of the group's name, without
//       reflectance (reflectance_missing) or emission.
#include <string>

#include "fuzz_support.h"
#include "mesh/read_stl.h"

using namespace radwalk;
using namespace radwalk::fuzz;

namespace {

const std::string kStlPath = "fuzz/scene.stl";

void check_stl_mesh(const Mesh& mesh) {
  check_read_mesh(mesh);
  RADWALK_FUZZ_CHECK(mesh.materials.size() == mesh.groups.size(), "one material per solid");
  for (std::size_t g = 0; g < mesh.groups.size(); ++g) {
    RADWALK_FUZZ_CHECK(mesh.materials[g].name == mesh.group_name[g], "material " + std::to_string(g) + ": named by its solid");
    RADWALK_FUZZ_CHECK(mesh.materials[g].reflectance_missing, "material " + std::to_string(g) + ": STL gives no rho");
    RADWALK_FUZZ_CHECK((mesh.materials[g].Ke == 0).all(), "material " + std::to_string(g) + ": STL gives no emission");
  }
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    for (int k = 0; k < mesh.corner_count(f); ++k)
      RADWALK_FUZZ_CHECK(static_cast<std::size_t>(mesh.faces[f][static_cast<std::size_t>(k)]) < mesh.vertices.size(),
                         "face " + std::to_string(f) + ": corner out of range");
    RADWALK_FUZZ_CHECK(mesh.face_material[f] == mesh.face_group[f], "face " + std::to_string(f) + ": material of its solid");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Mesh mesh;
  if (!accepts([&] { mesh = read_stl_bytes(kStlPath, as_text(data, size)); }, {kStlPath})) return 0;
  check_stl_mesh(mesh);
  check_warnings(mesh, {kStlPath});
  return 0;
}
