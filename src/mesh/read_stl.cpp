#include "mesh/read_stl.h"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>

#include "core/error.h"
#include "core/excerpt.h"
#include "mesh/exact_vertices.h"
#include "mesh/polygon_faces.h"
#include "mesh/text_scan.h"
#include "mesh/triangulate.h"

namespace radwalk {
namespace {

constexpr std::uint64_t kBinaryHeader = 84;  // 80 bytes of text, then the 4-byte triangle count
constexpr std::uint64_t kBinaryFacet = 50;   // 12 floats and a 2-byte attribute

std::string stem_of(const std::string& path) {
  const std::string stem = std::filesystem::path(path).stem().string();
  return stem.empty() ? "stl" : stem;
}

// Adds a group (and the material of the same name, without reflectance) for a solid; returns its index.
std::int32_t add_solid(Mesh& mesh, const std::string& name) {
  for (std::size_t g = 0; g < mesh.group_name.size(); ++g)
    if (mesh.group_name[g] == name) return static_cast<std::int32_t>(g);
  mesh.groups.push_back("group '" + name + "'");
  mesh.group_object.push_back("");
  mesh.group_name.push_back(name);
  Material m;
  m.name = name;
  m.reflectance_missing = true;
  mesh.materials.push_back(m);
  return static_cast<std::int32_t>(mesh.groups.size() - 1);
}

// The material of group g: add_solid keeps them in step (material g is group g's).
std::int32_t material_of_group(std::int32_t g) { return g; }


// A little-endian 32-bit value at `at`, whatever the machine's byte order.
std::uint32_t load_u32(const char* at) {
  const auto* b = reinterpret_cast<const unsigned char*>(at);
  return static_cast<std::uint32_t>(b[0]) | static_cast<std::uint32_t>(b[1]) << 8 |
         static_cast<std::uint32_t>(b[2]) << 16 | static_cast<std::uint32_t>(b[3]) << 24;
}

float load_float(const char* at) {
  const std::uint32_t bits = load_u32(at);
  float v;
  std::memcpy(&v, &bits, 4);
  return v;
}

bool is_binary(std::string_view bytes) {
  if (bytes.size() < kBinaryHeader) return false;
  const std::uint32_t n = load_u32(bytes.data() + 80);
  return bytes.size() == kBinaryHeader + kBinaryFacet * static_cast<std::uint64_t>(n);
}

Mesh read_binary(const std::string& path, std::string_view bytes, const ReadOptions& options) {
  static_assert(sizeof(float) == 4, "binary STL floats are IEEE single precision");
  const std::uint64_t n = (bytes.size() - kBinaryHeader) / kBinaryFacet;
  if (n > static_cast<std::uint64_t>(std::numeric_limits<std::int32_t>::max() / 3))
    throw InputError(locate(path, 0, -1, "binary STL of " + std::to_string(n) + " triangles: too many faces"));
  Mesh mesh;
  mesh.path = path;
  const std::int32_t group = add_solid(mesh, stem_of(path));
  ExactVertices vertices(mesh.vertices);
  PolygonFaces faces(mesh, options.strict);
  const char* at = bytes.data() + kBinaryHeader;
  for (std::uint64_t t = 0; t < n; ++t, at += kBinaryFacet) {
    std::vector<std::int32_t> corners(3);
    for (int k = 0; k < 3; ++k) {
      const char* c = at + 12 + 12 * k;
      corners[static_cast<std::size_t>(k)] =
          vertices.index(Vec3(load_float(c), load_float(c + 4), load_float(c + 8)));
    }
    faces.add(corners, 0, material_of_group(group), group, static_cast<std::int32_t>(t));
  }
  return mesh;
}

// The ascii grammar as a small state machine over statements (text_scan.h line rule and tokens).
Mesh read_ascii(const std::string& path, std::string_view bytes, const ReadOptions& options) {
  Mesh mesh;
  mesh.path = path;
  ExactVertices vertices(mesh.vertices);
  PolygonFaces faces(mesh, options.strict);
  enum class State { outside, in_solid, in_facet, in_loop, loop_done };
  State state = State::outside;
  std::int32_t group = -1;
  std::string solid;
  long unnamed = 0;
  std::int32_t facet = 0;
  long facet_line = 0;
  std::vector<std::int32_t> corners;
  const std::string stem = stem_of(path);
  auto expected = [&](long line, std::string_view got, const char* want) {
    throw InputError(locate(path, line, -1, "expected " + std::string(want) + ", found '" + excerpt(got) + "'"));
  };
  for_each_line(bytes, [&](long line, std::string_view content) {
    const auto tokens = split_tokens(content);
    if (tokens.empty()) return;
    const std::string_view key = tokens[0];
    switch (state) {
      case State::outside: {
        if (key != "solid") expected(line, content, "'solid NAME'");
        solid = tokens.size() > 1 ? std::string(rest_of_statement(content, tokens[1])) : "";
        if (solid.empty()) solid = ++unnamed == 1 ? stem : stem + "_" + std::to_string(unnamed);
        group = add_solid(mesh, solid);
        state = State::in_solid;
        return;
      }
      case State::in_solid: {
        if (key == "endsolid") {
          state = State::outside;
          return;
        }
        if (key != "facet" || tokens.size() != 5 || tokens[1] != "normal")
          expected(line, content, "'facet normal nx ny nz' or 'endsolid'");
        for (int k = 2; k < 5; ++k)
          if (!parse_double(tokens[static_cast<std::size_t>(k)]))
            throw InputError(locate(path, line, facet, "facet normal: '" + excerpt(tokens[static_cast<std::size_t>(k)]) +
                                                           "' is not a number"));
        if (facet == std::numeric_limits<std::int32_t>::max())
          throw InputError(locate(path, line, -1, "too many facets"));
        facet_line = line;
        state = State::in_facet;
        return;
      }
      case State::in_facet:
        if (key != "outer" || tokens.size() != 2 || tokens[1] != "loop") expected(line, content, "'outer loop'");
        corners.clear();
        state = State::in_loop;
        return;
      case State::in_loop: {
        if (key == "endloop") {
          state = State::loop_done;
          return;
        }
        if (key != "vertex" || tokens.size() != 4) expected(line, content, "'vertex x y z' or 'endloop'");
        Vec3 p;
        for (int k = 0; k < 3; ++k) {
          const auto x = parse_double(tokens[static_cast<std::size_t>(k) + 1]);
          if (!x)
            throw InputError(locate(path, line, facet, "vertex: '" + excerpt(tokens[static_cast<std::size_t>(k) + 1]) +
                                                           "' is not a number"));
          p[k] = *x;  // non-finite coordinates are kept: validate_mesh refuses the faces that use them
        }
        if (corners.size() >= kMaxPolygonCorners)
          throw InputError(locate(path, line, facet, "more than " + std::to_string(kMaxPolygonCorners) +
                                                         " vertices in one facet"));
        corners.push_back(vertices.index(p));
        return;
      }
      case State::loop_done:
        if (key != "endfacet") expected(line, content, "'endfacet'");
        if (corners.size() < 3)
          mesh.findings.push_back(mesh.finding_of(facet, facet_line, material_of_group(group), group,
                                                  "face of fewer than 3 corners", Severity::error,
                                                  "has " + std::to_string(corners.size()) +
                                                      " vertices, a face needs at least 3"));
        else
          faces.add(corners, facet_line, material_of_group(group), group, facet);
        ++facet;
        state = State::in_solid;
        return;
    }
  });
  if (state != State::outside)
    throw InputError(locate(path, 0, -1, "file ends inside solid '" + excerpt(solid) + "' (truncated file?)"));
  if (mesh.groups.empty()) throw InputError(locate(path, 0, -1, "empty file: no 'solid'"));
  return mesh;
}

}  // namespace

Mesh read_stl(const std::string& path, const ReadOptions& options) {
  return read_stl_bytes(path, read_input_file(path), options);
}

Mesh read_stl_bytes(const std::string& path, std::string_view bytes, const ReadOptions& options) {
  static_assert(std::numeric_limits<float>::is_iec559, "binary STL floats are IEEE single precision");
  if (is_binary(bytes)) return read_binary(path, bytes, options);
  std::size_t start = bytes.substr(0, 3) == "\xEF\xBB\xBF" ? 3 : 0;
  while (start < bytes.size() && (bytes[start] == ' ' || bytes[start] == '\t' || bytes[start] == '\r' ||
                                  bytes[start] == '\n'))
    ++start;
  // Ascii STL is text: a NUL byte, or a byte other than printable ASCII and blanks where a binary file has its
  // count (bytes 80 to 83), makes it a binary file whose count does not match (its header may start with "solid").
  bool text = bytes.find('\0') == std::string_view::npos;
  for (std::size_t k = 80; k < 84 && k < bytes.size(); ++k) {
    const auto c = static_cast<unsigned char>(bytes[k]);
    text = text && ((c >= 0x20 && c < 0x7F) || c == '\t' || c == '\r' || c == '\n');
  }
  const bool ascii = text && bytes.substr(start, 5) == "solid" &&
                     (start + 5 == bytes.size() || std::strchr(" \t\r\n", bytes[start + 5]) != nullptr);
  if (ascii) return read_ascii(path, bytes, options);
  if (bytes.size() >= kBinaryHeader) {
    const std::uint64_t n = load_u32(bytes.data() + 80);
    throw InputError(locate(path, 0, -1,
                            "binary STL declares " + std::to_string(n) + " triangles (84 + 50 x " + std::to_string(n) +
                                " = " + std::to_string(kBinaryHeader + kBinaryFacet * n) + " bytes) but the file has " +
                                std::to_string(bytes.size()) + " bytes (truncated file or wrong count)"));
  }
  throw InputError(locate(path, 0, -1, "not an STL file (neither 'solid' ascii nor a binary STL of 84 + 50 n bytes)"));
}

}  // namespace radwalk
