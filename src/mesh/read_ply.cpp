#include "mesh/read_ply.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/excerpt.h"
#include "mesh/polygon_faces.h"
#include "mesh/text_scan.h"
#include "mesh/triangulate.h"

namespace radwalk {

namespace {

enum class PlyType { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

std::optional<PlyType> ply_type(std::string_view name) {
  static const std::pair<std::string_view, PlyType> kNames[] = {
      {"char", PlyType::int8},      {"int8", PlyType::int8},       {"uchar", PlyType::uint8},
      {"uint8", PlyType::uint8},    {"short", PlyType::int16},     {"int16", PlyType::int16},
      {"ushort", PlyType::uint16},  {"uint16", PlyType::uint16},   {"int", PlyType::int32},
      {"int32", PlyType::int32},    {"uint", PlyType::uint32},     {"uint32", PlyType::uint32},
      {"float", PlyType::float32},  {"float32", PlyType::float32}, {"double", PlyType::float64},
      {"float64", PlyType::float64}};
  for (const auto& [n, t] : kNames)
    if (n == name) return t;
  return std::nullopt;
}

std::size_t type_size(PlyType t) {
  switch (t) {
    case PlyType::int8:
    case PlyType::uint8: return 1;
    case PlyType::int16:
    case PlyType::uint16: return 2;
    case PlyType::int32:
    case PlyType::uint32:
    case PlyType::float32: return 4;
    case PlyType::float64: return 8;
  }
  return 1;
}

bool is_float(PlyType t) { return t == PlyType::float32 || t == PlyType::float64; }

// A value read from the file, for a message: the shortest text that reads back to it (an ascii index or
// length may be 1e30, which no integer type holds; to_string would print a colour of -1e-7 as "-0.000000").
std::string value_text(double v) {
  char buf[32];
  return std::string(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
}

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::float32;  // the value type, or the item type of a list
  bool list = false;
  PlyType count_type = PlyType::uint8;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  long line = 0;  // header line of the element statement
  std::vector<PlyProperty> properties;
  // Bytes (binary) or values (ascii) an element takes at the least: a list counts as its count alone.
  std::uint64_t minimum_size(bool binary) const {
    std::uint64_t s = 0;
    for (const auto& p : properties) s += binary ? type_size(p.list ? p.count_type : p.type) : 1;
    return s;
  }
};

enum class PlyFormat { ascii, little_endian, big_endian };

struct PlyHeader {
  PlyFormat format = PlyFormat::ascii;
  std::vector<PlyElement> elements;
  std::size_t body = 0;  // byte offset of the body
  long body_line = 0;    // line number of the body's first line (ascii)
};

PlyHeader parse_header(const std::string& path, std::string_view bytes) {
  PlyHeader h;
  std::size_t at = 0;
  long line = 0;
  bool format_seen = false;
  for (;;) {
    const std::size_t end = bytes.find('\n', at);
    if (end == std::string_view::npos)
      throw InputError(locate(path, 0, -1, "PLY header has no end_header (truncated file?)"));
    std::string_view text = bytes.substr(at, end - at);
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    at = end + 1;
    ++line;
    const auto tokens = split_tokens(text);
    if (line == 1) {
      if (tokens.size() != 1 || tokens[0] != "ply")
        throw InputError(locate(path, 1, -1, "not a PLY file (the first line is not 'ply')"));
      continue;
    }
    if (tokens.empty() || tokens[0] == "comment" || tokens[0] == "obj_info") continue;
    const std::string_view key = tokens[0];
    if (key == "format") {
      if (tokens.size() != 3) throw InputError(locate(path, line, -1, "malformed format statement"));
      if (tokens[1] == "ascii") h.format = PlyFormat::ascii;
      else if (tokens[1] == "binary_little_endian") h.format = PlyFormat::little_endian;
      else if (tokens[1] == "binary_big_endian") h.format = PlyFormat::big_endian;
      else throw InputError(locate(path, line, -1, "unknown PLY format '" + excerpt(tokens[1]) + "'"));
      format_seen = true;
    } else if (key == "element") {
      const auto count = tokens.size() == 3 ? parse_long(tokens[2]) : std::nullopt;
      if (!count || *count < 0)
        throw InputError(locate(path, line, -1, "malformed element statement (expected 'element NAME COUNT')"));
      h.elements.push_back({std::string(tokens[1]), static_cast<std::uint64_t>(*count), line, {}});
    } else if (key == "property") {
      if (h.elements.empty()) throw InputError(locate(path, line, -1, "property before the first element"));
      PlyProperty p;
      bool ok = false;
      if (tokens.size() == 5 && tokens[1] == "list") {
        const auto c = ply_type(tokens[2]), t = ply_type(tokens[3]);
        ok = c && t && !is_float(*c);
        if (ok) {
          p.list = true;
          p.count_type = *c;
          p.type = *t;
          p.name = std::string(tokens[4]);
        }
      } else if (tokens.size() == 3) {
        const auto t = ply_type(tokens[1]);
        ok = t.has_value();
        if (ok) {
          p.type = *t;
          p.name = std::string(tokens[2]);
        }
      }
      if (!ok)
        throw InputError(locate(path, line, -1, "malformed property statement '" + excerpt(text) +
                                                    "' (expected 'property TYPE NAME' or 'property list "
                                                    "COUNT_TYPE ITEM_TYPE NAME' with integer COUNT_TYPE)"));
      h.elements.back().properties.push_back(p);
    } else if (key == "end_header") {
      if (!format_seen) throw InputError(locate(path, line, -1, "PLY header has no format statement"));
      h.body = at;
      h.body_line = line + 1;
      return h;
    } else {
      throw InputError(locate(path, line, -1, "unknown PLY header statement '" + excerpt(key) + "'"));
    }
  }
}

// Reads the values of the body in order: ascii tokens across lines, or binary numbers of either byte order.
class PlyReader {
 public:
  PlyReader(const std::string& path, std::string_view bytes, const PlyHeader& header)
      : path_(path), bytes_(bytes), at_(header.body), line_(header.body_line), format_(header.format) {}

  // The next value as a double (exact for every PLY type); `what` names it in messages.
  double value(PlyType type, const std::string& what) {
    if (format_ == PlyFormat::ascii) return ascii_value(type, what);
    const std::size_t n = type_size(type);
    if (bytes_.size() - at_ < n)
      throw InputError(locate(path_, 0, -1, "file ends inside " + what + " (truncated file?)"));
    std::array<unsigned char, 8> b{};
    std::memcpy(b.data(), bytes_.data() + at_, n);
    at_ += n;
    const bool swap = (format_ == PlyFormat::big_endian) != (std::endian::native == std::endian::big);
    if (swap) std::reverse(b.begin(), b.begin() + static_cast<std::ptrdiff_t>(n));
    switch (type) {
      case PlyType::int8: return static_cast<double>(static_cast<std::int8_t>(b[0]));
      case PlyType::uint8: return static_cast<double>(b[0]);
      case PlyType::int16: return static_cast<double>(load<std::int16_t>(b));
      case PlyType::uint16: return static_cast<double>(load<std::uint16_t>(b));
      case PlyType::int32: return static_cast<double>(load<std::int32_t>(b));
      case PlyType::uint32: return static_cast<double>(load<std::uint32_t>(b));
      case PlyType::float32: return static_cast<double>(load<float>(b));
      case PlyType::float64: return load<double>(b);
    }
    return 0;
  }
  // The line of the next ascii value (0 for binary files).
  long line() {
    if (format_ != PlyFormat::ascii) return 0;
    skip_space();
    return line_;
  }
  std::size_t remaining() const { return bytes_.size() - at_; }

 private:
  template <class T>
  static T load(const std::array<unsigned char, 8>& b) {
    T v;
    std::memcpy(&v, b.data(), sizeof(T));
    return v;
  }
  void skip_space() {
    while (at_ < bytes_.size() && (bytes_[at_] == ' ' || bytes_[at_] == '\t' || bytes_[at_] == '\r' ||
                                   bytes_[at_] == '\n')) {
      if (bytes_[at_] == '\n') ++line_;
      ++at_;
    }
  }
  double ascii_value(PlyType type, const std::string& what) {
    skip_space();
    if (at_ >= bytes_.size()) throw InputError(locate(path_, line_, -1, "file ends before " + what + " (truncated file?)"));
    std::size_t end = at_;
    while (end < bytes_.size() && bytes_[end] != ' ' && bytes_[end] != '\t' && bytes_[end] != '\r' &&
           bytes_[end] != '\n')
      ++end;
    const std::string_view token = bytes_.substr(at_, end - at_);
    at_ = end;
    const ParsedNumber n = parse_number(token);
    if (n.status != NumberStatus::ok)
      throw InputError(locate(path_, line_, -1, what + ": '" + excerpt(token) + "' is not " +
                                                    (n.status == NumberStatus::out_of_range ? "in range" : "a number")));
    if (!is_float(type) && std::floor(n.value) != n.value)
      throw InputError(locate(path_, line_, -1, what + ": '" + excerpt(token) + "' is not an integer"));
    return n.value;
  }

  const std::string& path_;
  std::string_view bytes_;
  std::size_t at_;
  long line_;
  PlyFormat format_;
};

int property_index(const PlyElement& e, std::initializer_list<std::string_view> names) {
  for (std::size_t k = 0; k < e.properties.size(); ++k)
    for (std::string_view n : names)
      if (e.properties[k].name == n) return static_cast<int>(k);
  return -1;
}

}  // namespace

Mesh read_ply(const std::string& path, const ReadOptions& options) {
  return read_ply_bytes(path, read_input_file(path), options);
}

Mesh read_ply_bytes(const std::string& path, std::string_view bytes, const ReadOptions& options) {
  const PlyHeader header = parse_header(path, bytes);
  const bool binary = header.format != PlyFormat::ascii;
  const PlyElement* vertex_element = nullptr;
  const PlyElement* face_element = nullptr;
  for (const PlyElement& e : header.elements) {
    if (e.name == "vertex" && !vertex_element) vertex_element = &e;
    if (e.name == "face" && !face_element) face_element = &e;
  }
  if (!face_element) throw InputError(locate(path, 0, -1, "PLY file has no face element"));
  if (!vertex_element) throw InputError(locate(path, 0, -1, "PLY file has no vertex element"));
  // Every count must fit the bytes left (a bound on every allocation below).
  std::uint64_t needed = 0;
  const std::uint64_t available = bytes.size() - header.body;
  for (const PlyElement& e : header.elements) {
    const std::uint64_t each = std::max<std::uint64_t>(1, e.minimum_size(binary));
    if (e.count > available / each || needed + e.count * each > available)
      throw InputError(locate(path, e.line, -1, "element '" + excerpt(e.name) + "' declares " +
                                                    std::to_string(e.count) + " items, but only " +
                                                    std::to_string(available) +
                                                    " bytes follow the header (truncated file or wrong count)"));
    needed += e.count * each;
  }
  const int px = property_index(*vertex_element, {"x"}), py = property_index(*vertex_element, {"y"}),
            pz = property_index(*vertex_element, {"z"});
  if (px < 0 || py < 0 || pz < 0 || vertex_element->properties[static_cast<std::size_t>(px)].list)
    throw InputError(locate(path, vertex_element->line, -1, "the vertex element has no x, y and z properties"));
  const int pv = property_index(*face_element, {"vertex_indices", "vertex_index"});
  if (pv < 0 || !face_element->properties[static_cast<std::size_t>(pv)].list)
    throw InputError(locate(path, face_element->line, -1, "the face element has no vertex_indices list"));
  const int pr = property_index(*face_element, {"red"}), pg = property_index(*face_element, {"green"}),
            pb = property_index(*face_element, {"blue"});
  const bool coloured = pr >= 0 && pg >= 0 && pb >= 0;
  if (vertex_element->count > static_cast<std::uint64_t>(std::numeric_limits<std::int32_t>::max()) ||
      face_element->count > static_cast<std::uint64_t>(std::numeric_limits<std::int32_t>::max()))
    throw InputError(locate(path, 0, -1, "too many vertices or faces (at most 2^31 - 1 each)"));

  Mesh mesh;
  mesh.path = path;
  if (!coloured) {
    Material m;
    m.name = "ply_default";
    m.Kd = Rgb::Constant(0.5);
    mesh.materials.push_back(m);
    mesh.findings.push_back(mesh.finding_of(-1, 0, -1, -1, "no face colours", Severity::warning,
                                            "no face colours: every face gets reflectance 0.5"));
  }
  std::map<std::array<double, 3>, int> material_of_colour;

  PlyReader in(path, bytes, header);
  PolygonFaces polygons(mesh, options.strict);
  for (const PlyElement& e : header.elements) {
    const bool is_vertex = &e == vertex_element, is_face = &e == face_element;
    if (is_vertex) mesh.vertices.reserve(e.count);
    if (is_face) {
      mesh.faces.reserve(e.count);
      mesh.face_line.reserve(e.count);
      mesh.face_material.reserve(e.count);
      mesh.face_source.reserve(e.count);
      mesh.face_group.reserve(e.count);
    }
    for (std::uint64_t item = 0; item < e.count; ++item) {
      const long line = in.line();
      const long face = is_face ? static_cast<long>(item) : -1;
      const std::string what = is_vertex ? "vertex " + std::to_string(item + 1)
                               : is_face ? "face " + std::to_string(item)
                                         : excerpt(e.name) + " " + std::to_string(item);
      Vec3 point = Vec3::Zero();
      std::vector<std::int32_t> corners;
      // A face's own defects are collected (one finding each, the face left out, the scene refused after
      // validation with every finding, as the OBJ reader does); the values are still read, so the next face is.
      std::vector<std::pair<std::string, std::string>> face_errors;  // kind, message
      std::array<double, 3> colour{};
      for (std::size_t k = 0; k < e.properties.size(); ++k) {
        const PlyProperty& p = e.properties[k];
        const std::string value_name = what + " " + printable(p.name);
        if (!p.list) {
          const double v = in.value(p.type, value_name);
          if (is_vertex && (static_cast<int>(k) == px || static_cast<int>(k) == py || static_cast<int>(k) == pz)) {
            if (!std::isfinite(v))
              throw InputError(locate(path, line, -1, what + " has a non-finite coordinate"));
            point[static_cast<int>(k) == px ? 0 : static_cast<int>(k) == py ? 1 : 2] = v;
          }
          if (is_face && coloured && (static_cast<int>(k) == pr || static_cast<int>(k) == pg || static_cast<int>(k) == pb)) {
            const double top = is_float(p.type) ? 1.0 : 255.0;
            if (!(v >= 0 && v <= top))
              face_errors.emplace_back("colour out of range", "colour " + p.name + " = " + value_text(v) +
                                                                  " is outside 0.." + (is_float(p.type) ? "1" : "255"));
            colour[static_cast<int>(k) == pr ? 0 : static_cast<int>(k) == pg ? 1 : 2] = v / top;
          }
          continue;
        }
        const double n = in.value(p.count_type, value_name + " count");
        if (n < 0) throw InputError(locate(path, line, face, "negative list length"));
        if (n > static_cast<double>(in.remaining()))
          throw InputError(
              locate(path, line, face, "list length " + value_text(n) + " runs past the end of the file"));
        const auto count = static_cast<std::size_t>(n);
        const bool indices = is_face && static_cast<int>(k) == pv;
        if (indices && count < 3)
          face_errors.emplace_back("face of fewer than 3 corners",
                                   "has " + std::to_string(count) + " vertices, a face needs at least 3");
        if (indices && count > kMaxPolygonCorners)
          face_errors.emplace_back("polygon of too many corners",
                                   "has " + std::to_string(count) + " vertices, more than the " +
                                       std::to_string(kMaxPolygonCorners) + " radwalk triangulates; split the polygon");
        bool bad_index = false;
        for (std::size_t c = 0; c < count; ++c) {
          const double v = in.value(p.type, value_name + " entry " + std::to_string(c));
          if (!indices) continue;
          if (!(v >= 0 && v < static_cast<double>(vertex_element->count))) {
            if (!bad_index)
              face_errors.emplace_back("bad vertex index", "vertex index " + value_text(v) + " is out of range (" +
                                                               std::to_string(vertex_element->count) + " vertices)");
            bad_index = true;
            continue;
          }
          corners.push_back(static_cast<std::int32_t>(v));
        }
      }
      if (is_vertex) mesh.vertices.push_back(point);
      if (!is_face) continue;
      if (!face_errors.empty()) {
        for (const auto& [kind, message] : face_errors)
          mesh.findings.push_back(mesh.finding_of(face, line, -1, -1, kind, Severity::error, message));
        continue;
      }
      int material = 0;
      if (coloured) {
        auto it = material_of_colour.find(colour);
        if (it == material_of_colour.end()) {
          Material m;
          const bool bytes_colour = !is_float(face_element->properties[static_cast<std::size_t>(pr)].type);
          m.name = bytes_colour ? "ply_" + std::to_string(std::lround(colour[0] * 255)) + "_" +
                                      std::to_string(std::lround(colour[1] * 255)) + "_" +
                                      std::to_string(std::lround(colour[2] * 255))
                                : "ply_colour_" + std::to_string(material_of_colour.size());
          m.Kd = Rgb(colour[0], colour[1], colour[2]);
          it = material_of_colour.emplace(colour, static_cast<int>(mesh.materials.size())).first;
          mesh.materials.push_back(m);
        }
        material = it->second;
      }
      polygons.add(corners, line, material, -1, static_cast<std::int32_t>(item));
    }
  }
  return mesh;
}

}  // namespace radwalk
