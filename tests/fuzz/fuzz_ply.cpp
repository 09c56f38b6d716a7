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

void check_ply_mesh(const Mesh& mesh) {
  const std::size_t n = mesh.face_count();
  RADWALK_FUZZ_CHECK(mesh.face_material.size() == n && mesh.face_line.size() == n,
                     "per-face arrays of another size");
  for (const Vec3& p : mesh.vertices) RADWALK_FUZZ_CHECK(p.allFinite(), "a non-finite vertex was read");
  for (std::size_t f = 0; f < n; ++f) {
    const std::string face = "face " + std::to_string(f);
    for (int k = 0; k < mesh.corner_count(f); ++k) {
      const std::int32_t v = mesh.faces[f][static_cast<std::size_t>(k)];
      RADWALK_FUZZ_CHECK(v >= 0 && static_cast<std::size_t>(v) < mesh.vertices.size(),
                         face + ": corner out of range");
    }
    RADWALK_FUZZ_CHECK(mesh.faces[f][3] >= -1, face + ": fourth corner");
    const std::int32_t m = mesh.face_material[f];
    RADWALK_FUZZ_CHECK(m >= 0 && static_cast<std::size_t>(m) < mesh.materials.size(),
                       face + ": material index");
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
