// Fuzz harness: the VTK polydata reader path (mesh/read_vtk.h, read_vtk_polydata_bytes), XML .vtp and legacy .vtk,
// then validation (mesh/validate.h), as the CLI and radwalk.load take a .vtp/.vtk scene.
//
// Input: the bytes of one VTK file: "fuzz/scene.vtp" (the XML reader) when the first byte that is not white space
// is '<', else "fuzz/scene.vtk" (the legacy reader).
// Contract: read_vtk_polydata_bytes returns a Mesh or throws InputError. Both formats are read by radwalk's own
// readers, every bound checked where it is read: a .vtp by mesh/vtp_xml.h and mesh/vtk_data_array.h, a legacy .vtk
// by mesh/vtk_legacy.h (ASCII and BINARY, classic and version 5 cells); libFuzzer's -malloc_limit_mb turns an
// allocation beyond the bounds into a finding, ASan an out-of-bounds read or write.
// Oracles:
//   (a) a refusal is one line of printable UTF-8 that starts with the file's path; so is every warning;
//   (reader) an accepted Mesh is what read_vtk.h promises: faces of 3 or 4 corners, each a vertex; materials -1
//       or an index; every material's Ke finite and its Kd finite unless missing (a file without rho);
//   (b) validate_mesh accepts it or refuses it in one line (a), and what it accepts passes check_validated_mesh.
#include <cstddef>
#include <string>

#include "fuzz_support.h"
#include "mesh/read_vtk.h"
#include "mesh/validate.h"

using namespace radwalk;
using namespace radwalk::fuzz;

namespace {

void check_vtk_mesh(const Mesh& mesh) {
  check_read_mesh(mesh);
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    for (int k = 0; k < mesh.corner_count(f); ++k)
      RADWALK_FUZZ_CHECK(static_cast<std::size_t>(mesh.faces[f][static_cast<std::size_t>(k)]) < mesh.vertices.size(),
                         "face " + std::to_string(f) + ": corner out of range");
    RADWALK_FUZZ_CHECK(mesh.face_material[f] < static_cast<std::int32_t>(mesh.materials.size()),
                       "face " + std::to_string(f) + ": material out of range");
  }
  for (const Material& m : mesh.materials) {
    // A file without rho still gives its E (read_vtk.h): the missing Kd is what validation refuses, naming --set.
    RADWALK_FUZZ_CHECK(m.Ke.allFinite(), "material '" + m.name + "': Ke not finite");
    if (!m.reflectance_missing) RADWALK_FUZZ_CHECK(m.Kd.allFinite(), "material '" + m.name + "': rho not finite");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes = as_text(data, size);
  const std::size_t first = bytes.find_first_not_of(" \t\r\n");
  const bool xml = first != std::string_view::npos && bytes[first] == '<';
  const std::string path = xml ? "fuzz/scene.vtp" : "fuzz/scene.vtk";
  Mesh mesh;
  if (!accepts([&] { mesh = read_vtk_polydata_bytes(path, bytes, xml); }, {path})) return 0;
  check_vtk_mesh(mesh);
  check_warnings(mesh, {path});
  // A file without rho is refused by validation with the --set that gives one; give it one, as --set does, so
  // that the later steps are fuzzed too.
  for (Material& m : mesh.materials)
    if (m.reflectance_missing) {
      m.reflectance_missing = false;
      m.Kd = Rgb::Constant(0.5);
    }
  if (!accepts([&] { validate_mesh(mesh); }, {path})) return 0;
  check_validated_mesh(mesh);
  check_warnings(mesh, {path});
  return 0;
}
