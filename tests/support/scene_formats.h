#pragma once
// One triangle scene written in every format radwalk reads (OBJ + MTL, ascii STL, binary STL, glTF with an
// external .bin, GLB), for the tests that compare the readers: every coordinate is a multiple of 1/4, so that the
// float32 formats (binary STL, glTF) hold it exactly and every reader must give the same vertices, faces, areas
// and so the same radiosity. Groups are runs of triangles; each group's material has the group's name.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace radwalk::test {

struct TriScene {
  std::vector<std::array<double, 3>> vertices;
  struct Triangle {
    std::array<int, 3> v;  // 0-based, counter-clockwise seen from the front
    std::string group;     // also the material's name
  };
  std::vector<Triangle> triangles;
  struct Colour {
    std::array<double, 3> kd, ke;
  };
  std::map<std::string, Colour> materials;  // by group name
};

// A closed 4 x 4 x 4 box facing inwards (walls "white", one wall "red", the ceiling "light" emitting Ke 1) with a
// 2 x 2 panel ("panel") floating at z = 1 facing up, 14 triangles.
inline TriScene box_with_panel() {
  TriScene s;
  s.materials["white"] = {{0.5, 0.5, 0.5}, {0, 0, 0}};
  s.materials["red"] = {{0.625, 0.125, 0.125}, {0, 0, 0}};
  s.materials["light"] = {{0, 0, 0}, {1, 1, 1}};
  s.materials["panel"] = {{0.75, 0.75, 0.75}, {0, 0, 0}};
  auto quad = [&](std::array<std::array<double, 3>, 4> p, const std::string& group) {
    const int base = static_cast<int>(s.vertices.size());
    for (const auto& q : p) s.vertices.push_back(q);
    s.triangles.push_back({{base, base + 1, base + 2}, group});
    s.triangles.push_back({{base, base + 2, base + 3}, group});
  };
  const double L = 4;
  // Inward-facing walls: corners counter-clockwise seen from inside.
  quad({{{0, 0, 0}, {0, L, 0}, {L, L, 0}, {L, 0, 0}}}, "white");  // floor, normal +z
  quad({{{0, 0, 0}, {L, 0, 0}, {L, 0, L}, {0, 0, L}}}, "white");  // y = 0, normal +y
  quad({{{0, L, 0}, {0, L, L}, {L, L, L}, {L, L, 0}}}, "white");  // y = L, normal -y
  quad({{{0, 0, 0}, {0, 0, L}, {0, L, L}, {0, L, 0}}}, "red");    // x = 0, normal +x
  quad({{{L, 0, 0}, {L, L, 0}, {L, L, L}, {L, 0, L}}}, "white");  // x = L, normal -x
  quad({{{0, 0, L}, {L, 0, L}, {L, L, L}, {0, L, L}}}, "light");  // ceiling, normal -z
  quad({{{1, 1, 1}, {3, 1, 1}, {3, 3, 1}, {1, 3, 1}}}, "panel");  // panel, normal +z
  return s;
}

inline std::string number(double x) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", x);
  return b;
}

// dir/NAME.obj and dir/NAME.mtl.
inline std::filesystem::path write_obj(const TriScene& s, const std::filesystem::path& dir, const std::string& name) {
  std::ofstream mtl(dir / (name + ".mtl"));
  for (const auto& [m, c] : s.materials)
    mtl << "newmtl " << m << "\nKd " << number(c.kd[0]) << ' ' << number(c.kd[1]) << ' ' << number(c.kd[2])
        << "\nKe " << number(c.ke[0]) << ' ' << number(c.ke[1]) << ' ' << number(c.ke[2]) << "\n";
  const auto path = dir / (name + ".obj");
  std::ofstream obj(path);
  obj << "mtllib " << name << ".mtl\n";
  for (const auto& v : s.vertices) obj << "v " << number(v[0]) << ' ' << number(v[1]) << ' ' << number(v[2]) << '\n';
  std::string group;
  for (const auto& t : s.triangles) {
    if (t.group != group) obj << "g " << t.group << "\nusemtl " << t.group << '\n';
    group = t.group;
    obj << "f " << t.v[0] + 1 << ' ' << t.v[1] + 1 << ' ' << t.v[2] + 1 << '\n';
  }
  return path;
}

// Ascii STL: one solid per run of a group.
inline std::string ascii_stl(const TriScene& s) {
  std::string out, group;
  for (const auto& t : s.triangles) {
    if (t.group != group) {
      if (!group.empty()) out += "endsolid " + group + "\n";
      out += "solid " + t.group + "\n";
      group = t.group;
    }
    out += "  facet normal 0 0 0\n    outer loop\n";
    for (int k : t.v) {
      const auto& p = s.vertices[static_cast<std::size_t>(k)];
      out += "      vertex " + number(p[0]) + " " + number(p[1]) + " " + number(p[2]) + "\n";
    }
    out += "    endloop\n  endfacet\n";
  }
  return out + "endsolid " + group + "\n";
}

inline void put_u32(std::string& out, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) out.push_back(static_cast<char>((v >> (8 * k)) & 0xFF));
}
inline void put_f32(std::string& out, double v) {
  const auto f = static_cast<float>(v);
  std::uint32_t bits;
  std::memcpy(&bits, &f, 4);
  put_u32(out, bits);
}

// Binary STL (one solid: the groups are lost), the header starting with "solid" as many exporters write it.
inline std::string binary_stl(const TriScene& s) {
  std::string out = "solid exported by a test";
  out.resize(80, ' ');
  put_u32(out, static_cast<std::uint32_t>(s.triangles.size()));
  for (const auto& t : s.triangles) {
    for (int k = 0; k < 3; ++k) put_f32(out, 0);
    for (int k : t.v)
      for (int c = 0; c < 3; ++c) put_f32(out, s.vertices[static_cast<std::size_t>(k)][static_cast<std::size_t>(c)]);
    out.append(2, '\0');
  }
  return out;
}

// The glTF JSON and its binary buffer: one node (named "node_GROUP", translated by `shift`, its positions stored
// shifted back) and one mesh (named GROUP) per run of a group, indices as unsigned shorts; materials with
// baseColorFactor = Kd and emissiveFactor x KHR_materials_emissive_strength = Ke. `uri` names the buffer's file
// ("" for a .glb's BIN chunk).
inline std::pair<std::string, std::string> gltf(const TriScene& s, const std::string& uri, double shift = 0.5) {
  std::string bin, views, accessors, meshes, nodes, node_list, materials;
  std::map<std::string, int> material_index;
  for (const auto& [m, c] : s.materials) {
    const double strength = std::max({c.ke[0], c.ke[1], c.ke[2], 1.0});
    material_index[m] = static_cast<int>(material_index.size());
    materials += std::string(materials.empty() ? "" : ",") + "{\"name\":\"" + m +
                 "\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[" + number(c.kd[0]) + "," + number(c.kd[1]) +
                 "," + number(c.kd[2]) + ",1]},\"emissiveFactor\":[" + number(c.ke[0] / strength) + "," +
                 number(c.ke[1] / strength) + "," + number(c.ke[2] / strength) +
                 "],\"extensions\":{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":" + number(strength) +
                 "}}}";
  }
  int n_views = 0, n_meshes = 0;
  for (std::size_t first = 0; first < s.triangles.size();) {
    std::size_t last = first;
    while (last < s.triangles.size() && s.triangles[last].group == s.triangles[first].group) ++last;
    const std::string group = s.triangles[first].group;
    // Positions: the run's corners in order (3 per triangle), shifted back by `shift`; indices 0, 1, 2, ...
    const std::size_t corners = 3 * (last - first);
    const std::size_t pos_offset = bin.size();
    for (std::size_t t = first; t < last; ++t)
      for (int k : s.triangles[t].v)
        for (int c = 0; c < 3; ++c) put_f32(bin, s.vertices[static_cast<std::size_t>(k)][static_cast<std::size_t>(c)] - shift);
    const std::size_t index_offset = bin.size();
    for (std::size_t k = 0; k < corners; ++k) {
      bin.push_back(static_cast<char>(k & 0xFF));
      bin.push_back(static_cast<char>(k >> 8));
    }
    while (bin.size() % 4) bin.push_back('\0');
    auto sep = [](const std::string& list) { return std::string(list.empty() ? "" : ","); };
    views += sep(views) + "{\"buffer\":0,\"byteOffset\":" + std::to_string(pos_offset) +
             ",\"byteLength\":" + std::to_string(12 * corners) + "}";
    views += ",{\"buffer\":0,\"byteOffset\":" + std::to_string(index_offset) +
             ",\"byteLength\":" + std::to_string(2 * corners) + "}";
    accessors += sep(accessors) + "{\"bufferView\":" + std::to_string(n_views) +
                 ",\"componentType\":5126,\"count\":" + std::to_string(corners) + ",\"type\":\"VEC3\"}";
    accessors += ",{\"bufferView\":" + std::to_string(n_views + 1) + ",\"componentType\":5123,\"count\":" +
                 std::to_string(corners) + ",\"type\":\"SCALAR\"}";
    meshes += sep(meshes) + "{\"name\":\"" + group + "\",\"primitives\":[{\"attributes\":{\"POSITION\":" +
              std::to_string(n_views) + "},\"indices\":" + std::to_string(n_views + 1) +
              ",\"material\":" + std::to_string(material_index[group]) + "}]}";
    nodes += sep(nodes) + "{\"name\":\"node_" + group + "\",\"mesh\":" + std::to_string(n_meshes) +
             ",\"translation\":[" + number(shift) + "," + number(shift) + "," + number(shift) + "]}";
    node_list += sep(node_list) + std::to_string(n_meshes);
    n_views += 2;
    ++n_meshes;
    first = last;
  }
  const std::string buffer = "{\"byteLength\":" + std::to_string(bin.size()) +
                             (uri.empty() ? "" : ",\"uri\":\"" + uri + "\"") + "}";
  std::string json = "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[" + node_list +
                     "]}],\"nodes\":[" + nodes + "],\"meshes\":[" + meshes + "],\"materials\":[" + materials +
                     "],\"accessors\":[" + accessors + "],\"bufferViews\":[" + views + "],\"buffers\":[" + buffer +
                     "],\"extensionsUsed\":[\"KHR_materials_emissive_strength\"]}";
  return {json, bin};
}

// A .glb of a glTF JSON and its binary buffer.
inline std::string glb(std::string json, std::string bin) {
  while (json.size() % 4) json.push_back(' ');
  while (bin.size() % 4) bin.push_back('\0');
  std::string out;
  put_u32(out, 0x46546C67);
  put_u32(out, 2);
  put_u32(out, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
  put_u32(out, static_cast<std::uint32_t>(json.size()));
  put_u32(out, 0x4E4F534A);
  out += json;
  put_u32(out, static_cast<std::uint32_t>(bin.size()));
  put_u32(out, 0x004E4942);
  out += bin;
  return out;
}

inline std::filesystem::path write_file(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

// Writes scene.obj (+ .mtl), scene_ascii.stl, scene_binary.stl, scene.gltf (+ scene.bin), scene.glb into dir.
inline void write_all_formats(const TriScene& s, const std::filesystem::path& dir) {
  write_obj(s, dir, "scene");
  write_file(dir / "scene_ascii.stl", ascii_stl(s));
  write_file(dir / "scene_binary.stl", binary_stl(s));
  const auto [json, bin] = gltf(s, "scene.bin");
  write_file(dir / "scene.gltf", json);
  write_file(dir / "scene.bin", bin);
  const auto [json2, bin2] = gltf(s, "");
  write_file(dir / "scene.glb", glb(json2, bin2));
}

// The --set options that give an STL of the scene its materials (Kd and Ke per group).
inline std::string set_options(const TriScene& s) {
  std::string out;
  for (const auto& [m, c] : s.materials)
    out += " --set " + m + ".Kd=" + number(c.kd[0]) + "," + number(c.kd[1]) + "," + number(c.kd[2]) + " --set " + m +
           ".Ke=" + number(c.ke[0]) + "," + number(c.ke[1]) + "," + number(c.ke[2]);
  return out;
}

}  // namespace radwalk::test
