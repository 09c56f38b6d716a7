// Fuzz harness: the OBJ + MTL reader (mesh/read_obj.h, read_obj_text), with tinyobjloader as an independent
// reference parse of the same bytes.
//
// Input: the bytes of an OBJ file, optionally followed by kMtlSeparator ("\n@@MTL@@\n") and the bytes of one
// MTL library. The OBJ is "fuzz/scene.obj". Every material library it names whose resolved path has no space
// or tab holds the MTL bytes; a path with a space or tab does not exist (so that both readings of an mtllib
// statement, one name with spaces or a list of names, are reached).
//
// Contract: read_obj_text returns a Mesh or throws InputError; nothing else (a crash, a sanitizer report,
// another exception type) is allowed.
// Oracles:
//   (a) a refusal is one line of printable UTF-8 that starts with the OBJ's path or a library's path; so is
//       every warning of an accepted file;
//   (reader) an accepted Mesh is well-formed: one line, material (-1 or an index) and 3 or 4 corners per
//       face, the corners non-negative, lines increasing, finite vertices;
//   (d) whenever radwalk accepts the file (no error finding, finite coordinates) and the bytes lie in the subset where the two parsers are
//       specified to agree (in_reference_subset below), tinyobjloader accepts it too and agrees on the
//       vertices (to 1e-12 relative: its number parser is not correctly rounded), on the faces with their
//       corners in order and on each face's material name. Outside the subset the comparison is skipped,
//       not the run.
#include <algorithm>
#include <tiny_obj_loader.h>

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "mesh/read_obj.h"

using namespace radwalk;
using namespace radwalk::fuzz;

namespace {

const std::string kObjPath = "fuzz/scene.obj";

bool blank(char c) {
  return c == ' ' || c == '\t';
}

// The lines of a text as both parsers split it: at "\n", "\r\n" or a lone "\r".
std::vector<std::string_view> lines_of(std::string_view text) {
  std::vector<std::string_view> lines;
  while (!text.empty()) {
    const std::size_t end = text.find_first_of("\r\n");
    lines.push_back(text.substr(0, end));
    if (end == std::string_view::npos) break;
    const std::size_t next =
        text[end] == '\r' && end + 1 < text.size() && text[end + 1] == '\n' ? end + 2 : end + 1;
    text.remove_prefix(next);
  }
  return lines;
}

std::vector<std::string_view> blank_separated(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && blank(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !blank(line[i])) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

// [+-]? followed by 1 to 9 digits, not all zero: an index atoi reads exactly and fixIndex accepts.
bool plain_index(std::string_view s) {
  if (!s.empty() && (s[0] == '+' || s[0] == '-')) s.remove_prefix(1);
  if (s.empty() || s.size() > 9) return false;
  bool nonzero = false;
  for (const char c : s) {
    if (c < '0' || c > '9') return false;
    nonzero = nonzero || c != '0';
  }
  return nonzero;
}

// A face corner both parsers read alike: V, V/T, V//N or V/T/N with plain indices.
bool plain_corner(std::string_view s) {
  const std::size_t a = s.find('/');
  if (a == std::string_view::npos) return plain_index(s);
  const std::string_view v = s.substr(0, a), rest = s.substr(a + 1);
  const std::size_t b = rest.find('/');
  if (b == std::string_view::npos) return plain_index(v) && plain_index(rest);
  const std::string_view t = rest.substr(0, b), n = rest.substr(b + 1);
  return plain_index(v) && (t.empty() || plain_index(t)) && plain_index(n);
}

// A coordinate tinyobjloader's own number parser reads to about 1e-14: at most 17 significant digits, zero or
// a magnitude in [1e-200, 1e200] (it scales by pow(5, exponent), which loses digits near the ends of the double
// range), and a written decimal exponent of at most 300 in magnitude (it reads "00e3020" as 0 x pow(5, 3020) =
// 0 x inf = NaN, where radwalk reads 0: regression-zero-huge-exponent.obj).
bool plain_coordinate(std::string_view s) {
  int digits = 0;
  bool leading = true;
  std::size_t exponent_at = std::string_view::npos;
  for (std::size_t k = 0; k < s.size(); ++k) {
    const char c = s[k];
    if (c == 'e' || c == 'E') {
      exponent_at = k + 1;
      break;
    }
    if (c >= '1' && c <= '9') leading = false;
    if (c >= '0' && c <= '9' && !leading) ++digits;
  }
  if (exponent_at != std::string_view::npos) {
    const std::string exponent(s.substr(exponent_at));
    const long e = std::strtol(exponent.c_str(), nullptr, 10);  // saturates at LONG_MAX: still above 300
    if (e > 300 || e < -300) return false;
  }
  const double x = std::strtod(std::string(s).c_str(), nullptr);
  return digits <= 17 && (x == 0 || (std::abs(x) >= 1e-200 && std::abs(x) <= 1e200));
}

// Rules both files share: no NUL (tinyobjloader parses C strings), no byte-order mark (radwalk skips it), no
// line continued by a trailing backslash (radwalk joins such lines), '#' only where a line's first token
// starts (radwalk ends every statement at a '#', tinyobjloader only skips comment lines).
bool common_subset(std::string_view text, const std::vector<std::string_view>& lines) {
  if (text.find('\0') != std::string_view::npos || text.substr(0, 3) == "\xEF\xBB\xBF") return false;
  for (const std::string_view line : lines) {
    if (!line.empty() && line.back() == '\\') return false;
    const std::size_t hash = line.find('#');
    if (hash != std::string_view::npos && hash != line.find_first_not_of(" \t")) return false;
  }
  return true;
}

// The subset of OBJ + MTL bytes where radwalk and tinyobjloader (2.0.0rc10) are specified to agree, beyond
// the common rules above:
//   OBJ: no `vw`, `l` or `p` statements (tinyobjloader fails on indices radwalk never reads); no keyword
//     that only starts with "usemtl" (tinyobjloader does not look for a blank after it); usemtl with exactly
//     one name without blanks (radwalk's name is the rest of the statement, tinyobjloader's one token), and
//     none before the first mtllib (tinyobjloader looks names up as it reads, radwalk after reading every
//     library); face corners V, V/T, V//N or V/T/N with plain non-zero indices (tinyobjloader reads them
//     with atoi); coordinates as plain_coordinate says.
//   MTL: every newmtl followed by exactly one blank and a name without blanks (tinyobjloader keeps further
//     leading blanks in the name).
bool in_reference_subset(std::string_view obj, std::string_view mtl) {
  const auto obj_lines = lines_of(obj), mtl_lines = lines_of(mtl);
  if (!common_subset(obj, obj_lines) || !common_subset(mtl, mtl_lines)) return false;
  bool mtllib_seen = false;
  for (const std::string_view line : obj_lines) {
    const auto tokens = blank_separated(line);
    if (tokens.empty()) continue;
    const std::string_view key = tokens[0];
    if (key == "vw" || key == "l" || key == "p") return false;
    if (key.substr(0, 6) == "usemtl" && (key != "usemtl" || tokens.size() != 2 || !mtllib_seen)) return false;
    if (key == "mtllib") mtllib_seen = true;
    if (key == "f") {
      // radwalk triangulates polygons of more than 4 corners (polygon_faces.h); tinyobjloader, called without
      // triangulation, keeps them whole, so the face lists are compared only without such polygons.
      if (tokens.size() > 5) return false;
      for (std::size_t k = 1; k < tokens.size(); ++k)
        if (!plain_corner(tokens[k])) return false;
    }
    if (key == "v")
      for (std::size_t k = 1; k < tokens.size() && k <= 3; ++k)
        if (!plain_coordinate(tokens[k])) return false;
  }
  for (const std::string_view line : mtl_lines) {
    const auto tokens = blank_separated(line);
    if (tokens.empty() || tokens[0] != "newmtl") continue;
    std::string_view rest = line.substr(line.find("newmtl") + 6);
    while (!rest.empty() && blank(rest.back())) rest.remove_suffix(1);
    if (tokens.size() != 2 || rest.size() < 2 || blank(rest[1])) return false;
  }
  return true;
}

// Oracle (d): tinyobjloader's reading of the same bytes must give the same vertices, faces and material
// names.
void compare_with_reference(const Mesh& mesh, std::string_view obj, std::string_view mtl) {
  std::istringstream obj_stream{std::string(obj)}, mtl_stream{std::string(mtl)};
  tinyobj::MaterialStreamReader mtl_reader(mtl_stream);
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  const bool loaded =
      tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &obj_stream, &mtl_reader, false);
  RADWALK_FUZZ_CHECK(loaded, "radwalk read the file, tinyobjloader refused it: " + err);

  RADWALK_FUZZ_CHECK(attrib.vertices.size() == 3 * mesh.vertices.size(),
                     "radwalk read " + std::to_string(mesh.vertices.size()) + " vertices, tinyobjloader " +
                         std::to_string(attrib.vertices.size() / 3));
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    for (int k = 0; k < 3; ++k) {
      const double x = mesh.vertices[v][k], y = attrib.vertices[3 * v + static_cast<std::size_t>(k)];
      RADWALK_FUZZ_CHECK(std::abs(x - y) <= 1e-12 * std::max(std::abs(x), std::abs(y)),
                         "vertex " + std::to_string(v + 1) + " coordinate " + std::to_string(k) +
                             ": radwalk " + std::to_string(x) + ", tinyobjloader " + std::to_string(y));
    }

  std::size_t f = 0;
  for (const auto& shape : shapes) {
    std::size_t offset = 0;
    for (std::size_t s = 0; s < shape.mesh.num_face_vertices.size(); ++s, ++f) {
      const std::size_t corners = shape.mesh.num_face_vertices[s];
      const std::string face = "face " + std::to_string(f);
      RADWALK_FUZZ_CHECK(f < mesh.face_count(), "tinyobjloader read more faces than radwalk");
      RADWALK_FUZZ_CHECK(corners == static_cast<std::size_t>(mesh.corner_count(f)),
                         face + ": corner counts differ");
      for (std::size_t k = 0; k < corners; ++k)
        RADWALK_FUZZ_CHECK(shape.mesh.indices[offset + k].vertex_index == mesh.faces[f][k],
                           face + ", corner " + std::to_string(k) + ": radwalk vertex " +
                               std::to_string(mesh.faces[f][k]) + ", tinyobjloader " +
                               std::to_string(shape.mesh.indices[offset + k].vertex_index));
      offset += corners;
      const int m = s < shape.mesh.material_ids.size() ? shape.mesh.material_ids[s] : -1;
      const std::string reference = m >= 0 ? materials[static_cast<std::size_t>(m)].name : "";
      const std::string ours = mesh.face_material[f] >= 0
                                   ? mesh.materials[static_cast<std::size_t>(mesh.face_material[f])].name
                                   : "";
      // A usemtl naming a material no library defines: radwalk gives the faces the default material under that
      // name (a repair), tinyobjloader no material.
      const bool undefined = reference.empty() && std::none_of(materials.begin(), materials.end(),
                                                               [&](const auto& m) { return m.name == ours; });
      RADWALK_FUZZ_CHECK(ours == reference || undefined, face + ": radwalk material '" + printable(ours) +
                                                             "', tinyobjloader '" + printable(reference) + "'");
    }
  }
  RADWALK_FUZZ_CHECK(f == mesh.face_count(), "radwalk read " + std::to_string(mesh.face_count()) +
                                                 " faces, tinyobjloader " + std::to_string(f));
}

// Faces in file order: lines grow with the input face; the pieces of a triangulated polygon share its input face
// and its line.
void check_face_lines(const Mesh& mesh) {
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const bool piece = f > 0 && mesh.source_face(f) == mesh.source_face(f - 1);
    RADWALK_FUZZ_CHECK(f == 0 || mesh.source_face(f) >= mesh.source_face(f - 1),
                       "face " + std::to_string(f) + ": input faces out of order");
    RADWALK_FUZZ_CHECK(mesh.face_line[f] > 0 && (f == 0 || (piece ? mesh.face_line[f] == mesh.face_line[f - 1]
                                                                    : mesh.face_line[f] > mesh.face_line[f - 1])),
                       "face " + std::to_string(f) + ": line " + std::to_string(mesh.face_line[f]));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto parts = split_at(as_text(data, size), kMtlSeparator);
  const std::string_view obj = parts.first, mtl = parts.second;
  std::vector<std::string> files{kObjPath};
  const MtlSource libraries = fuzz_libraries(mtl, files);
  Mesh mesh;
  if (!accepts([&] { mesh = read_obj_text(kObjPath, obj, libraries); }, files)) return 0;
  check_read_mesh(mesh);
  check_face_lines(mesh);
  check_warnings(mesh, files);
  // A file with per-face errors (collected as findings, the faces left out) or non-finite coordinates (kept for
  // validate_mesh to refuse) is refused once validated: each error is a refusal message, and there is no
  // reference comparison.
  bool refused = false;
  for (const Finding& f : mesh.findings)
    if (f.severity == Severity::error) {
      check_refusal_message(finding_line(f), files);
      refused = true;
    }
  for (const Vec3& p : mesh.vertices) refused = refused || !p.allFinite();
  if (refused) return 0;
  // Faces the reader repaired (fewer than 3 corners, repeated corners: polygon_faces.h) are not tinyobjloader's.
  for (const Finding& f : mesh.findings)
    if (f.kind == "face of fewer than 3 corners dropped" || f.kind == "repeated corners removed" ||
        f.kind == "face without area dropped")
      return 0;
  if (in_reference_subset(obj, mtl)) compare_with_reference(mesh, obj, mtl);
  return 0;
}
