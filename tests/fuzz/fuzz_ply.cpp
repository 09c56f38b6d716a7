// Fuzz harness: the PLY reader (mesh/read_ply.h, read_ply_bytes), ascii and both binary byte orders.
//
// Input: the bytes of one PLY file, "fuzz/scene.ply".
// Contract: read_ply_bytes returns a Mesh or throws InputError; it allocates no more than the bytes after the
// header can hold (libFuzzer's -malloc_limit_mb turns a larger allocation into a finding).
// Oracles:
//   (a) a refusal is one line of printable UTF-8 that starts with the file's path; so is every warning;
//   (reader) an accepted Mesh is what read_ply.h promises: finite vertices; faces of 3 or 4 corners, each a
//       vertex of the file; one material per face, every material a reflectance in [0, 1] without
//       emission; as many lines as faces.
#include <cmath>
#include <string>

#include "fuzz_support.h"
#include "mesh/read_ply.h"

using namespace radwalk;
using namespace radwalk::fuzz;

namespace {

const std::string kPlyPath = "fuzz/scene.ply";

// Beyond check_read_mesh: every corner a vertex of the file, every face a material, every material physical.
void check_ply_mesh(const Mesh& mesh) {
  check_read_mesh(mesh);
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const std::string face = "face " + std::to_string(f);
    for (int k = 0; k < mesh.corner_count(f); ++k)
      RADWALK_FUZZ_CHECK(
          static_cast<std::size_t>(mesh.faces[f][static_cast<std::size_t>(k)]) < mesh.vertices.size(),
          face + ": corner out of range");
    RADWALK_FUZZ_CHECK(mesh.face_material[f] >= 0, face + ": no material");
  }
  for (const Material& m : mesh.materials) {
    RADWALK_FUZZ_CHECK(m.Kd.allFinite() && (m.Kd >= 0).all() && (m.Kd <= 1).all(),
                       "material '" + m.name + "': reflectance outside [0, 1]");
    RADWALK_FUZZ_CHECK((m.Ke == 0).all(), "material '" + m.name + "': a PLY carries no emission");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Mesh mesh;
  if (!accepts([&] { mesh = read_ply_bytes(kPlyPath, as_text(data, size)); }, {kPlyPath})) return 0;
  check_ply_mesh(mesh);
  check_warnings(mesh, {kPlyPath});
  return 0;
}
