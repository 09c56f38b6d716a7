#include "mesh/read_gltf.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/excerpt.h"
#include "mesh/exact_vertices.h"
#include "mesh/polygon_faces.h"
#include "mesh/text_scan.h"

namespace radwalk {
namespace {

using Json = nlohmann::json;

constexpr int kMaxJsonDepth = 64;
constexpr std::uint32_t kGlbMagic = 0x46546C67;      // "glTF"
constexpr std::uint32_t kChunkJson = 0x4E4F534A;     // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942;      // "BIN\0"

std::uint32_t load_u32(const char* at) {
  const auto* b = reinterpret_cast<const unsigned char*>(at);
  return static_cast<std::uint32_t>(b[0]) | static_cast<std::uint32_t>(b[1]) << 8 |
         static_cast<std::uint32_t>(b[2]) << 16 | static_cast<std::uint32_t>(b[3]) << 24;
}

// Reads one glTF document into a Mesh; every refusal names the file and the glTF object.
class GltfReader {
 public:
  GltfReader(const std::string& path, std::string_view bytes, const GltfResources& resources,
             const ReadOptions& options)
      : path_(path), bytes_(bytes), resources_(resources), options_(options) {}

  Mesh read() {
    std::string_view text = bytes_;
    std::string_view bin;
    bool glb = false;
    if (bytes_.size() >= 4 && load_u32(bytes_.data()) == kGlbMagic) {
      glb = true;
      split_glb(text, bin);
    }
    doc_ = parse_json(text);
    if (!doc_.is_object()) fail("the document", "is not a JSON object");
    check_asset();
    check_required_extensions();
    // The budget of triangles and vertices made (instances counted): see read_gltf.h.
    budget_ = 1000000 + 8 * static_cast<std::uint64_t>(bytes_.size());
    load_buffers(glb, bin);
    mesh_.path = path_;
    load_materials();
    walk_scene();
    return std::move(mesh_);
  }

 private:
  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw InputError(locate(path_, 0, -1, where + ": " + what));
  }

  void split_glb(std::string_view& json, std::string_view& bin) {
    if (bytes_.size() < 20) fail("GLB header", "the file has " + std::to_string(bytes_.size()) + " bytes, fewer than a header and a chunk header (20)");
    const std::uint32_t version = load_u32(bytes_.data() + 4), length = load_u32(bytes_.data() + 8);
    if (version != 2) fail("GLB header", "version " + std::to_string(version) + " (radwalk reads glTF 2)");
    if (length != bytes_.size())
      fail("GLB header", "declares " + std::to_string(length) + " bytes but the file has " +
                             std::to_string(bytes_.size()) + " (truncated file?)");
    const std::uint64_t json_length = load_u32(bytes_.data() + 12);
    if (load_u32(bytes_.data() + 16) != kChunkJson) fail("GLB chunk 0", "is not the JSON chunk");
    if (json_length > bytes_.size() - 20)
      fail("GLB chunk 0", "declares " + std::to_string(json_length) + " bytes, more than the file holds");
    json = bytes_.substr(20, json_length);
    const std::uint64_t next = 20 + json_length;
    if (bytes_.size() - next < 8) return;  // no BIN chunk
    const std::uint64_t bin_length = load_u32(bytes_.data() + next);
    if (load_u32(bytes_.data() + next + 4) != kChunkBin) return;  // chunks of other types are skipped
    if (bin_length > bytes_.size() - next - 8)
      fail("GLB chunk 1", "declares " + std::to_string(bin_length) + " bytes, more than the file holds");
    bin = bytes_.substr(next + 8, bin_length);
  }

  Json parse_json(std::string_view text) {
    const Json::parser_callback_t depth_limit = [this](int depth, Json::parse_event_t, Json&) {
      if (depth > kMaxJsonDepth) fail("JSON", "nested more than " + std::to_string(kMaxJsonDepth) + " deep");
      return true;
    };
    try {
      return Json::parse(text.begin(), text.end(), depth_limit);
    } catch (const Json::exception& e) {
      fail("JSON", std::string("not valid JSON (") + excerpt(e.what()) + ")");
    }
  }

  // ---- typed access to the document ---------------------------------------------------------------------------
  static std::string at(const std::string& array, std::size_t k) { return array + "[" + std::to_string(k) + "]"; }

  const Json& array_of(const Json& object, const char* key, const std::string& where) const {
    static const Json kEmpty = Json::array();
    const auto it = object.find(key);
    if (it == object.end()) return kEmpty;
    if (!it->is_array()) fail(where, std::string("'") + key + "' is not an array");
    return *it;
  }

  const Json& object_at(const Json& array, std::size_t k, const std::string& where) const {
    if (!array[k].is_object()) fail(where, "is not a JSON object");
    return array[k];
  }

  // An integer property in [0, limit) (an index or a count below limit), or nullopt when absent.
  std::optional<std::uint64_t> unsigned_of(const Json& object, const char* key, const std::string& where,
                                           std::uint64_t limit) const {
    const auto it = object.find(key);
    if (it == object.end()) return std::nullopt;
    if (!it->is_number_unsigned() && !(it->is_number_integer() && it->get<std::int64_t>() >= 0))
      fail(where, std::string("'") + key + "' is not a non-negative integer");
    const auto v = it->get<std::uint64_t>();
    if (v >= limit) fail(where, std::string("'") + key + "' = " + std::to_string(v) + " is out of range (below " +
                                    std::to_string(limit) + " expected)");
    return v;
  }

  std::uint64_t required_unsigned(const Json& object, const char* key, const std::string& where,
                                  std::uint64_t limit) const {
    const auto v = unsigned_of(object, key, where, limit);
    if (!v) fail(where, std::string("has no '") + key + "'");
    return *v;
  }

  double number_of(const Json& value, const std::string& where) const {
    if (!value.is_number()) fail(where, "is not a number");
    const double v = value.get<double>();
    if (!std::isfinite(v)) fail(where, "is not finite");
    return v;
  }

  // n numbers of an array property, or `fallback` when absent.
  std::vector<double> numbers_of(const Json& object, const char* key, std::size_t n, const std::string& where,
                                 std::vector<double> fallback) const {
    const auto it = object.find(key);
    if (it == object.end()) return fallback;
    if (!it->is_array() || it->size() != n)
      fail(where, std::string("'") + key + "' is not an array of " + std::to_string(n) + " numbers");
    std::vector<double> v(n);
    for (std::size_t k = 0; k < n; ++k) v[k] = number_of((*it)[k], where + "." + key);
    return v;
  }

  std::string name_of(const Json& object) const {
    const auto it = object.find("name");
    return it != object.end() && it->is_string() ? it->get<std::string>() : std::string();
  }

  // ---- document level -----------------------------------------------------------------------------------------
  void check_asset() {
    const auto it = doc_.find("asset");
    if (it == doc_.end() || !it->is_object()) fail("asset", "missing (not a glTF 2.0 document)");
    const auto version = it->find("version");
    if (version == it->end() || !version->is_string()) fail("asset", "has no version");
    const std::string v = version->get<std::string>();
    if (v.rfind("2.", 0) != 0) fail("asset", "version '" + excerpt(v) + "' (radwalk reads glTF 2.x)");
  }

  void check_required_extensions() {
    static const char* const kHarmless[] = {"KHR_materials_emissive_strength", "KHR_materials_unlit",
                                            "KHR_texture_transform", "KHR_materials_ior", "KHR_materials_specular"};
    const Json& required = array_of(doc_, "extensionsRequired", "extensionsRequired");
    for (std::size_t k = 0; k < required.size(); ++k) {
      if (!required[k].is_string()) fail(at("extensionsRequired", k), "is not a string");
      const std::string name = required[k].get<std::string>();
      bool known = false;
      for (const char* h : kHarmless) known = known || name == h;
      if (!known)
        fail("extensionsRequired", "the file needs extension '" + excerpt(name) +
                                       "', which radwalk does not read (export the glTF without it)");
    }
  }

  static std::optional<std::string> base64_decode(std::string_view in) {
    auto value = [](char c) -> int {
      if (c >= 'A' && c <= 'Z') return c - 'A';
      if (c >= 'a' && c <= 'z') return c - 'a' + 26;
      if (c >= '0' && c <= '9') return c - '0' + 52;
      if (c == '+' || c == '-') return 62;
      if (c == '/' || c == '_') return 63;
      return -1;
    };
    while (!in.empty() && in.back() == '=') in.remove_suffix(1);
    std::string out;
    out.reserve(in.size() / 4 * 3 + 3);
    std::uint32_t acc = 0;
    int bits = 0;
    for (char c : in) {
      const int v = value(c);
      if (v < 0) return std::nullopt;
      acc = (acc << 6) | static_cast<std::uint32_t>(v);
      bits += 6;
      if (bits >= 8) {
        bits -= 8;
        out.push_back(static_cast<char>((acc >> bits) & 0xFF));
      }
    }
    return out;
  }

  static std::string percent_decode(const std::string& uri) {
    std::string out;
    for (std::size_t k = 0; k < uri.size(); ++k) {
      if (uri[k] == '%' && k + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[k + 1])) &&
          std::isxdigit(static_cast<unsigned char>(uri[k + 2]))) {
        out.push_back(static_cast<char>(std::stoi(uri.substr(k + 1, 2), nullptr, 16)));
        k += 2;
      } else {
        out.push_back(uri[k]);
      }
    }
    return out;
  }

  void load_buffers(bool glb, std::string_view bin) {
    const Json& buffers = array_of(doc_, "buffers", "buffers");
    owned_.reserve(buffers.size());  // views into owned_ stay valid: no reallocation
    for (std::size_t k = 0; k < buffers.size(); ++k) {
      const std::string where = at("buffers", k);
      const Json& b = object_at(buffers, k, where);
      const std::uint64_t length = required_unsigned(b, "byteLength", where, std::numeric_limits<std::uint64_t>::max());
      std::string_view data;
      const auto uri = b.find("uri");
      if (uri == b.end()) {
        if (!glb || k != 0) fail(where, "has no uri (only the first buffer of a .glb may use the BIN chunk)");
        data = bin;
      } else {
        if (!uri->is_string()) fail(where, "uri is not a string");
        const std::string u = uri->get<std::string>();
        if (u.rfind("data:", 0) == 0) {
          const std::size_t comma = u.find(',');
          if (comma == std::string::npos || u.compare(0, comma, "data:") == 0 ||
              u.substr(0, comma).find(";base64") == std::string::npos)
            fail(where, "data URI is not base64");
          auto decoded = base64_decode(std::string_view(u).substr(comma + 1));
          if (!decoded) fail(where, "data URI holds a character that is not base64");
          owned_.push_back(std::move(*decoded));
        } else {
          const std::string file = percent_decode(u);
          // A message that would quote bytes that are not printable UTF-8 (the uri may hold any; a fuzz finding) quotes
          // an excerpt instead.
          try {
            owned_.push_back(resources_.read(!file.empty() && file[0] == '/' ? file : directory_of(path_) + file));
          } catch (const InputError& e) {
            if (printable(e.what()) == e.what()) throw;
            fail(where, "buffer '" + excerpt(file) + "' cannot be read (" + excerpt(e.what()) + ")");
          }
        }
        data = owned_.back();
      }
      if (length > data.size())
        fail(where, "byteLength " + std::to_string(length) + " is more than its " + std::to_string(data.size()) +
                        " bytes of data");
      buffers_.push_back(data.substr(0, length));
    }
    const Json& views = array_of(doc_, "bufferViews", "bufferViews");
    for (std::size_t k = 0; k < views.size(); ++k) {
      const std::string where = at("bufferViews", k);
      const Json& v = object_at(views, k, where);
      const std::string_view buffer = buffers_[required_unsigned(v, "buffer", where, buffers_.size())];
      const std::uint64_t offset = unsigned_of(v, "byteOffset", where, buffer.size() + 1).value_or(0);
      const std::uint64_t length = required_unsigned(v, "byteLength", where, buffer.size() - offset + 1);
      const std::uint64_t stride = unsigned_of(v, "byteStride", where, 253).value_or(0);
      views_.push_back({buffer.substr(offset, length), stride});
    }
  }

  struct View {
    std::string_view data;
    std::uint64_t stride = 0;  // 0: tightly packed
  };

  struct Accessor {
    std::string_view data;  // from the first element on
    std::uint64_t stride = 0, count = 0;
    int component_type = 0, components = 0;
    std::size_t component_size = 0;
  };

  Accessor accessor(std::uint64_t index, const std::string& user) const {
    const std::string where = at("accessors", index);
    const Json& accessors = array_of(doc_, "accessors", "accessors");
    if (index >= accessors.size()) fail(user, "accessor " + std::to_string(index) + " does not exist");
    const Json& a = object_at(accessors, index, where);
    if (a.contains("sparse")) fail(where, "sparse accessors are not read by radwalk");
    const auto view_index = unsigned_of(a, "bufferView", where, views_.size());
    if (!view_index) fail(where, "has no bufferView (an accessor of zeros has no surface)");
    const View& view = views_[*view_index];
    Accessor r;
    r.component_type = static_cast<int>(required_unsigned(a, "componentType", where, 6000));
    switch (r.component_type) {
      case 5120: case 5121: r.component_size = 1; break;
      case 5122: case 5123: r.component_size = 2; break;
      case 5125: case 5126: r.component_size = 4; break;
      default: fail(where, "componentType " + std::to_string(r.component_type) + " is not a glTF component type");
    }
    const auto type = a.find("type");
    if (type == a.end() || !type->is_string()) fail(where, "has no type");
    static const std::pair<const char*, int> kTypes[] = {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4},
                                                         {"MAT2", 4},   {"MAT3", 9}, {"MAT4", 16}};
    for (const auto& [name, n] : kTypes)
      if (*type == name) r.components = n;
    if (r.components == 0) fail(where, "type '" + excerpt(type->get<std::string>()) + "' is not a glTF type");
    r.count = required_unsigned(a, "count", where, std::numeric_limits<std::uint32_t>::max());
    const std::uint64_t element = r.component_size * static_cast<std::uint64_t>(r.components);
    r.stride = view.stride ? view.stride : element;
    if (r.stride < element) fail(where, "byteStride " + std::to_string(r.stride) + " is shorter than an element");
    const std::uint64_t offset = unsigned_of(a, "byteOffset", where, view.data.size() + 1).value_or(0);
    // The last element must end inside the view (a bound on everything read through the accessor).
    const std::uint64_t room = view.data.size() - offset;
    if (r.count > 0 && (room < element || (r.count - 1) > (room - element) / r.stride))
      fail(where, std::to_string(r.count) + " elements of " + std::to_string(element) + " bytes (stride " +
                      std::to_string(r.stride) + ") do not fit the " + std::to_string(room) +
                      " bytes of its buffer view");
    r.data = view.data.substr(offset);
    return r;
  }

  static float float_at(const char* at) {
    const std::uint32_t bits = load_u32(at);
    float v;
    std::memcpy(&v, &bits, 4);
    return v;
  }

  static std::uint64_t index_at(const Accessor& a, std::uint64_t k) {
    const char* at = a.data.data() + k * a.stride;
    const auto* b = reinterpret_cast<const unsigned char*>(at);
    switch (a.component_type) {
      case 5121: return b[0];
      case 5123: return static_cast<std::uint64_t>(b[0]) | static_cast<std::uint64_t>(b[1]) << 8;
      default: return load_u32(at);
    }
  }

  void load_materials() {
    const Json& materials = array_of(doc_, "materials", "materials");
    for (std::size_t k = 0; k < materials.size(); ++k) {
      const std::string where = at("materials", k);
      const Json& m = object_at(materials, k, where);
      Material out;
      out.name = name_of(m);
      if (out.name.empty()) out.name = "material_" + std::to_string(k);
      std::vector<double> base = {1, 1, 1, 1};
      const auto pbr = m.find("pbrMetallicRoughness");
      if (pbr != m.end()) {
        if (!pbr->is_object()) fail(where, "pbrMetallicRoughness is not an object");
        base = numbers_of(*pbr, "baseColorFactor", 4, where + ".pbrMetallicRoughness", base);
        if (pbr->contains("baseColorTexture"))
          mesh_.findings.push_back(mesh_.finding_of(-1, 0, -1, -1, "texture ignored", Severity::warning,
                                                    "material '" + excerpt(out.name) +
                                                        "': baseColorTexture ignored, rho is baseColorFactor"));
      }
      const std::vector<double> emissive = numbers_of(m, "emissiveFactor", 3, where, {0, 0, 0});
      double strength = 1;
      const auto ext = m.find("extensions");
      if (ext != m.end() && ext->is_object()) {
        const auto s = ext->find("KHR_materials_emissive_strength");
        if (s != ext->end() && s->is_object() && s->contains("emissiveStrength"))
          strength = number_of((*s)["emissiveStrength"],
                               where + ".extensions.KHR_materials_emissive_strength.emissiveStrength");
      }
      const auto two = m.find("doubleSided");
      if (two != m.end()) {
        if (!two->is_boolean()) fail(where, "doubleSided is not true or false");
        out.two_sided = two->get<bool>();
      }
      out.Kd = Rgb(base[0], base[1], base[2]);
      out.Ke = Rgb(emissive[0], emissive[1], emissive[2]) * strength;
      mesh_.materials.push_back(out);
    }
  }

  // ---- scene graph ----------------------------------------------------------------------------------------------
  Eigen::Matrix4d local_transform(const Json& node, const std::string& where) const {
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    if (node.contains("matrix")) {
      const std::vector<double> v = numbers_of(node, "matrix", 16, where, {});
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) m(r, c) = v[static_cast<std::size_t>(4 * c + r)];  // column-major
      return m;
    }
    const std::vector<double> t = numbers_of(node, "translation", 3, where, {0, 0, 0});
    const std::vector<double> q = numbers_of(node, "rotation", 4, where, {0, 0, 0, 1});
    const std::vector<double> s = numbers_of(node, "scale", 3, where, {1, 1, 1});
    Eigen::Quaterniond rotation(q[3], q[0], q[1], q[2]);
    if (!(rotation.norm() > 0)) fail(where, "rotation is a zero quaternion");
    rotation.normalize();
    m.block<3, 3>(0, 0) = rotation.toRotationMatrix() * Eigen::Vector3d(s[0], s[1], s[2]).asDiagonal();
    m.block<3, 1>(0, 3) = Eigen::Vector3d(t[0], t[1], t[2]);
    return m;
  }

  std::int32_t group_for(const std::string& object, const std::string& group) {
    std::string label;
    if (!object.empty()) label = "object '" + object + "'";
    if (!group.empty()) label += (label.empty() ? "" : ", ") + ("group '" + group + "'");
    for (std::size_t g = 0; g < mesh_.groups.size(); ++g)
      if (mesh_.groups[g] == label) return static_cast<std::int32_t>(g);
    mesh_.groups.push_back(label);
    mesh_.group_object.push_back(object);
    mesh_.group_name.push_back(group);
    return static_cast<std::int32_t>(mesh_.groups.size() - 1);
  }

  void spend(std::uint64_t n, const std::string& where) {
    if (n > budget_)
      fail(where, "makes more triangles and vertices than the file's size allows (at most 1e6 + 8 per byte, "
                  "instances counted)");
    budget_ -= n;
  }

  void emit_mesh(std::uint64_t mesh_index, const Eigen::Matrix4d& transform, std::int32_t group,
                 ExactVertices& vertices, PolygonFaces& faces) {
    const Json& meshes = array_of(doc_, "meshes", "meshes");
    const std::string mesh_where = at("meshes", mesh_index);
    const Json& m = object_at(meshes, mesh_index, mesh_where);
    const Json& primitives = array_of(m, "primitives", mesh_where);
    const bool mirror = transform.block<3, 3>(0, 0).determinant() < 0;
    for (std::size_t p = 0; p < primitives.size(); ++p) {
      const std::string where = mesh_where + ".primitives[" + std::to_string(p) + "]";
      const Json& prim = object_at(primitives, p, where);
      const std::uint64_t mode = unsigned_of(prim, "mode", where, 7).value_or(4);
      if (mode < 4) {
        ++ignored_primitives_;
        continue;
      }
      const auto attributes = prim.find("attributes");
      if (attributes == prim.end() || !attributes->is_object()) fail(where, "has no attributes");
      const auto position_index = unsigned_of(*attributes, "POSITION", where + ".attributes", std::numeric_limits<std::uint32_t>::max());
      if (!position_index) fail(where, "has no POSITION attribute");
      const Accessor position = accessor(*position_index, where);
      if (position.component_type != 5126 || position.components != 3)
        fail(at("accessors", *position_index), "POSITION must be FLOAT VEC3 (quantized positions are not read)");
      std::int32_t material = -1;
      if (const auto mi = unsigned_of(prim, "material", where, mesh_.materials.size() + 0))
        material = static_cast<std::int32_t>(*mi);
      std::optional<Accessor> indices;
      if (const auto ii = unsigned_of(prim, "indices", where, std::numeric_limits<std::uint32_t>::max())) {
        indices = accessor(*ii, where);
        if (indices->components != 1 ||
            (indices->component_type != 5121 && indices->component_type != 5123 && indices->component_type != 5125))
          fail(at("accessors", *ii), "indices must be SCALAR of unsigned byte, short or int");
      }
      const std::uint64_t n = indices ? indices->count : position.count;
      const std::uint64_t triangles = mode == 4 ? n / 3 : (n >= 3 ? n - 2 : 0);
      spend(triangles + position.count, where);
      std::vector<std::int32_t> local(position.count);
      for (std::uint64_t k = 0; k < position.count; ++k) {
        const char* c = position.data.data() + k * position.stride;
        const Eigen::Vector4d x(float_at(c), float_at(c + 4), float_at(c + 8), 1.0);
        const Eigen::Vector4d y = transform * x;
        local[k] = vertices.index(Vec3(y[0], y[1], y[2]));
      }
      if (mode == 4 && n % 3 != 0)
        mesh_.findings.push_back(mesh_.finding_of(-1, 0, material, group, "leftover indices ignored",
                                                  Severity::warning,
                                                  where + ": " + std::to_string(n % 3) +
                                                      " indices after the last whole triangle ignored"));
      auto vertex = [&](std::uint64_t k) { return indices ? index_at(*indices, k) : k; };
      for (std::uint64_t t = 0; t < triangles; ++t) {
        std::uint64_t c[3];
        if (mode == 4) {
          c[0] = vertex(3 * t), c[1] = vertex(3 * t + 1), c[2] = vertex(3 * t + 2);
        } else if (mode == 5) {  // strip: every other triangle reversed, so all face one way
          c[0] = vertex(t), c[1] = vertex(t + 1 + t % 2), c[2] = vertex(t + 2 - t % 2);
        } else {  // fan around the first vertex
          c[0] = vertex(t + 1), c[1] = vertex(t + 2), c[2] = vertex(0);
        }
        if (mirror) std::swap(c[1], c[2]);
        const auto source = static_cast<std::int32_t>(face_count_);
        if (face_count_ == static_cast<std::uint64_t>(std::numeric_limits<std::int32_t>::max()))
          fail(where, "too many triangles");
        ++face_count_;
        std::vector<std::int32_t> corners;
        for (const std::uint64_t v : c) {
          if (v >= position.count) {
            mesh_.findings.push_back(mesh_.finding_of(source, 0, material, group, "bad vertex index",
                                                      Severity::error,
                                                      where + ": vertex index " + std::to_string(v) +
                                                          " is out of range (" + std::to_string(position.count) +
                                                          " vertices)"));
            corners.clear();
            break;
          }
          corners.push_back(local[v]);
        }
        if (!corners.empty()) faces.add(corners, 0, material, group, source);
      }
    }
  }

  void walk_scene() {
    ExactVertices vertices(mesh_.vertices);
    PolygonFaces faces(mesh_, options_.strict);
    const Json& nodes = array_of(doc_, "nodes", "nodes");
    const Json& meshes = array_of(doc_, "meshes", "meshes");
    std::vector<std::uint64_t> roots;
    const Json& scenes = array_of(doc_, "scenes", "scenes");
    if (!scenes.empty()) {
      const std::uint64_t s = unsigned_of(doc_, "scene", "scene", scenes.size()).value_or(0);
      const Json& scene = object_at(scenes, s, at("scenes", s));
      const Json& list = array_of(scene, "nodes", at("scenes", s));
      for (std::size_t k = 0; k < list.size(); ++k) {
        if (!list[k].is_number_unsigned() || list[k].get<std::uint64_t>() >= nodes.size())
          fail(at("scenes", s), "nodes[" + std::to_string(k) + "] is not a node index");
        roots.push_back(list[k].get<std::uint64_t>());
      }
    } else if (!nodes.empty()) {
      std::vector<bool> child(nodes.size(), false);
      for (std::size_t k = 0; k < nodes.size(); ++k) {
        const Json& children = array_of(object_at(nodes, k, at("nodes", k)), "children", at("nodes", k));
        for (const Json& c : children)
          if (c.is_number_unsigned() && c.get<std::uint64_t>() < nodes.size()) child[c.get<std::uint64_t>()] = true;
      }
      for (std::size_t k = 0; k < nodes.size(); ++k)
        if (!child[k]) roots.push_back(k);
    } else {
      for (std::size_t k = 0; k < meshes.size(); ++k) {
        std::string name = name_of(object_at(meshes, k, at("meshes", k)));
        if (name.empty()) name = "mesh_" + std::to_string(k);
        emit_mesh(k, Eigen::Matrix4d::Identity(), group_for("", name), vertices, faces);
      }
    }
    // Depth first, with an explicit stack (no recursion on a deep hierarchy); a node reached twice is refused.
    std::vector<bool> visited(nodes.size(), false);
    std::vector<std::pair<std::uint64_t, Eigen::Matrix4d>> stack;
    for (auto r = roots.rbegin(); r != roots.rend(); ++r) stack.emplace_back(*r, Eigen::Matrix4d::Identity());
    while (!stack.empty()) {
      const auto [k, parent] = stack.back();
      stack.pop_back();
      const std::string where = at("nodes", k);
      if (visited[k]) fail(where, "is reached twice (a cycle, or a child of two parents)");
      visited[k] = true;
      const Json& node = object_at(nodes, k, where);
      const Eigen::Matrix4d global = parent * local_transform(node, where);
      if (!global.allFinite()) fail(where, "its transform is not finite");
      if (const auto mi = unsigned_of(node, "mesh", where, meshes.size())) {
        std::string object = name_of(node), group = name_of(object_at(meshes, *mi, at("meshes", *mi)));
        if (object.empty()) object = "node_" + std::to_string(k);
        if (group.empty()) group = "mesh_" + std::to_string(*mi);
        emit_mesh(*mi, global, group_for(object, group), vertices, faces);
      }
      const Json& children = array_of(node, "children", where);
      for (std::size_t c = children.size(); c-- > 0;) {
        if (!children[c].is_number_unsigned() || children[c].get<std::uint64_t>() >= nodes.size())
          fail(where, "children[" + std::to_string(c) + "] is not a node index");
        stack.emplace_back(children[c].get<std::uint64_t>(), global);
      }
    }
    if (ignored_primitives_ > 0)
      mesh_.findings.push_back(mesh_.finding_of(-1, 0, -1, -1, "points and lines ignored", Severity::warning,
                                                std::to_string(ignored_primitives_) +
                                                    " primitives of points or lines ignored: radiosity needs surfaces"));
  }

  const std::string& path_;
  std::string_view bytes_;
  const GltfResources& resources_;
  ReadOptions options_;
  Json doc_;
  Mesh mesh_;
  std::vector<std::string> owned_;
  std::vector<std::string_view> buffers_;
  std::vector<View> views_;
  std::uint64_t budget_ = 0;
  std::uint64_t face_count_ = 0;
  long ignored_primitives_ = 0;
};

}  // namespace

GltfResources gltf_files_on_disk() {
  return {[](const std::string& file) { return read_input_file(file); }};
}

Mesh read_gltf(const std::string& path, const ReadOptions& options) {
  return read_gltf_bytes(path, read_input_file(path), gltf_files_on_disk(), options);
}

Mesh read_gltf_bytes(const std::string& path, std::string_view bytes, const GltfResources& resources,
                     const ReadOptions& options) {
  return GltfReader(path, bytes, resources, options).read();
}

}  // namespace radwalk
