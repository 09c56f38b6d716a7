// Fuzz harness: validation and patching (mesh/validate.h, patch/patching.h) of scenes read from fuzzed bytes.
//
// Input: a PLY file if the bytes start with "ply" and a line break, else an OBJ with an optional MTL library
// as in fuzz_obj_mtl.cpp (OBJ bytes, kMtlSeparator, MTL bytes). Inputs above kMaxInput bytes are skipped,
// which bounds the work of one run (faces, and with the max edge below at most 64 patches per face).
// Contract: read, then validate_mesh, then make_patches(mesh, 0) and make_patches(mesh, max_edge) with
// max_edge = sqrt(3) x (largest extent of the scene's bounding box) / k, k = 2 + input size % 7 (so no edge
// is cut into more than 8 parts); the reader and validation return or throw InputError, nothing else;
// patching a validated mesh with these max edges returns.
// Oracles:
//   (a) a refusal (of the reader or validation) is one line of printable UTF-8 that starts with the scene's
//       path or a library's; so is every warning;
//   (b) an accepted mesh has faces, each with a finite positive area and a material with rho in [0, 1) and
//       finite Ke >= 0 and E = pi Ke (check_validated_mesh); validation is idempotent (a mesh it accepted
//       and repaired is accepted again, unchanged); the patches of both patchings keep their faces'
//       materials and their areas add up to their face's area within rounding (check_patches).
#include <algorithm>
#include <cmath>
#include <string>

#include "fuzz_support.h"
#include "mesh/read_obj.h"
#include "mesh/read_ply.h"
#include "mesh/validate.h"
#include "patch/patching.h"

using namespace radwalk;
using namespace radwalk::fuzz;

namespace {

constexpr std::size_t kMaxInput = 16 * 1024;
const std::string kObjPath = "fuzz/scene.obj", kPlyPath = "fuzz/scene.ply";

bool is_ply(std::string_view input) {
  return input.substr(0, 4) == "ply\n" || input.substr(0, 5) == "ply\r\n";
}

bool same_mesh(const Mesh& a, const Mesh& b) {
  if (a.faces != b.faces || a.face_material != b.face_material || a.materials.size() != b.materials.size())
    return false;
  for (std::size_t m = 0; m < a.materials.size(); ++m)
    if (a.materials[m].name != b.materials[m].name) return false;
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > kMaxInput) return 0;
  const std::string_view input = as_text(data, size);
  std::vector<std::string> files;
  Mesh mesh;
  bool read = false;
  if (is_ply(input)) {
    files.push_back(kPlyPath);
    read = accepts([&] { mesh = read_ply_bytes(kPlyPath, input); }, files);
  } else {
    const auto parts = split_at(input, kMtlSeparator);
    files.push_back(kObjPath);
    const MtlSource libraries = fuzz_libraries(parts.second, files);
    read = accepts([&] { mesh = read_obj_text(kObjPath, parts.first, libraries); }, files);
  }
  if (!read || !accepts([&] { validate_mesh(mesh); }, files)) return 0;
  check_validated_mesh(mesh);
  check_warnings(mesh, files);

  Mesh again = mesh;
  RADWALK_FUZZ_CHECK(accepts([&] { validate_mesh(again); }, files), "validation refuses a mesh it accepted");
  RADWALK_FUZZ_CHECK(same_mesh(mesh, again), "validating a validated mesh changed it");

  // Patching refuses only a NaN max edge or too many patches: neither can happen here.
  PatchSet whole;
  RADWALK_FUZZ_CHECK(accepts([&] { whole = make_patches(mesh, 0); }, files),
                     "patching refuses a validated mesh");
  check_patches(mesh, whole, 0);
  // sqrt(3) x the largest extent of the bounding box is at least its diagonal, so at least every edge.
  const double max_edge = std::sqrt(3.0) * whole.scene_extent() / static_cast<double>(2 + size % 7);
  PatchSet split;
  RADWALK_FUZZ_CHECK(accepts([&] { split = make_patches(mesh, max_edge); }, files),
                     "patching refuses a validated mesh with max edge " + std::to_string(max_edge));
  check_patches(mesh, split, max_edge);
  return 0;
}
