#include "mesh/read_ply.h"

#include <fstream>
#include <map>
#include <sstream>

// GCC 12 reports a false -Wmaybe-uninitialized inside OpenMesh's property vectors of Vec3uc colours.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include "core/error.h"
#include "mesh/text_scan.h"

namespace radwalk {

namespace {

struct PlyTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Color = OpenMesh::Vec3uc;
};
using PlyMesh = OpenMesh::PolyMesh_ArrayKernelT<PlyTraits>;

// What the header says, read independently of OpenMesh.
struct PlyHeader {
  bool ascii = false;
  long header_lines = 0;
  long faces = -1;                  // -1: no face element
  long elements_before_faces = 0;   // sum of counts of the elements before "element face"
};

PlyHeader scan_ply_header(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(locate(path, 0, -1, "cannot open the file"));
  PlyHeader h;
  std::string line;
  bool seen_faces = false;
  while (std::getline(in, line)) {
    ++h.header_lines;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto tokens = split_tokens(line);
    if (h.header_lines == 1 && (tokens.empty() || tokens[0] != "ply"))
      throw InputError(locate(path, 1, -1, "not a PLY file (first line is not 'ply')"));
    if (tokens.empty()) continue;
    if (tokens[0] == "format" && tokens.size() >= 2) h.ascii = tokens[1] == "ascii";
    if (tokens[0] == "element") {
      const auto count = tokens.size() == 3 ? parse_long(tokens[2]) : std::nullopt;
      if (!count || *count < 0) throw InputError(locate(path, h.header_lines, -1, "malformed element statement"));
      if (tokens[1] == "face") {
        h.faces = *count;
        seen_faces = true;
      } else if (!seen_faces) {
        h.elements_before_faces += *count;
      }
    }
    if (tokens[0] == "end_header") return h;
  }
  throw InputError(locate(path, 0, -1, "PLY header has no end_header (truncated file?)"));
}

// Captures OpenMesh's error stream while alive. OpenMesh's mostream::disconnect() forgets, without deleting, the
// target that connect() allocated, so connecting and disconnecting per read would leak; instead omerr() is
// redirected once, for the life of the process, into one stream that each capture empties first.
class OmerrCapture {
 public:
  OmerrCapture() : captured_(stream()) {
    captured_.str("");
    captured_.clear();
  }
  OmerrCapture(const OmerrCapture&) = delete;
  OmerrCapture& operator=(const OmerrCapture&) = delete;
  std::vector<std::string> lines() const {
    std::vector<std::string> out;
    std::istringstream s(captured_.str());
    for (std::string l; std::getline(s, l);)
      if (!l.empty()) out.push_back(l);
    return out;
  }

 private:
  static std::ostringstream& stream() {
    // Never deleted: omerr() may still write to it while static objects are destroyed at exit.
    static std::ostringstream* const captured = [] {
      auto* s = new std::ostringstream;
      ::omerr().disconnect(std::cerr);
      ::omerr().connect(*s);
      return s;
    }();
    return *captured;
  }

  std::ostringstream& captured_;
};

}  // namespace

Mesh read_ply(const std::string& path) {
  const PlyHeader header = scan_ply_header(path);
  if (header.faces < 0) throw InputError(locate(path, 0, -1, "PLY file has no face element"));

  PlyMesh om;
  om.request_face_colors();
  OpenMesh::IO::Options options = OpenMesh::IO::Options::FaceColor;
  std::vector<std::string> messages;
  bool ok = false;
  {
    OmerrCapture capture;
    ok = OpenMesh::IO::read_mesh(om, path, options);
    messages = capture.lines();
  }
  auto joined = [&] {
    std::string s;
    for (std::size_t i = 0; i < messages.size() && i < 3; ++i) s += (i ? "; " : " (OpenMesh: ") + messages[i];
    return messages.empty() ? s : s + ")";
  };
  if (!ok) throw InputError(locate(path, 0, -1, "OpenMesh could not read this PLY file" + joined()));

  // Nothing may vanish: OpenMesh must return every face of the header.
  const long read_faces = static_cast<long>(om.n_faces());
  if (read_faces != header.faces)
    throw InputError(locate(path, 0, -1, "header declares " + std::to_string(header.faces) + " faces but OpenMesh read " +
                                             std::to_string(read_faces) +
                                             " (faces with repeated vertex indices are dropped)" + joined()));

  Mesh mesh;
  mesh.path = path;
  for (std::string& m : messages) mesh.warnings.push_back(locate(path, 0, -1, "OpenMesh: " + m));

  mesh.vertices.reserve(om.n_vertices());
  for (const auto vh : om.vertices()) {
    const auto& p = om.point(vh);
    mesh.vertices.emplace_back(p[0], p[1], p[2]);
  }

  const bool coloured = options.face_has_color();
  if (!coloured) {
    Material m;
    m.name = "ply_default";
    m.Kd = Rgb::Constant(0.5);
    mesh.materials.push_back(m);
    mesh.warnings.push_back(locate(path, 0, -1, "no face colours: every face gets reflectance 0.5"));
  }
  std::map<std::array<int, 3>, int> material_of_colour;

  for (const auto fh : om.faces()) {
    const long f = fh.idx();
    const long line = header.ascii ? header.header_lines + header.elements_before_faces + f + 1 : 0;
    std::array<std::int32_t, 4> corners{-1, -1, -1, -1};
    int k = 0;
    for (const auto vh : om.fv_range(fh)) {
      if (k == 4)
        throw InputError(locate(path, line, f, "has " + std::to_string(om.valence(fh)) +
                                                   " vertices; radwalk takes triangles and quads only"));
      corners[static_cast<std::size_t>(k++)] = vh.idx();
    }
    if (k < 3) throw InputError(locate(path, line, f, "has fewer than 3 vertices"));
    mesh.faces.push_back(corners);
    mesh.face_line.push_back(line);

    int material = 0;
    if (coloured) {
      const auto c = om.color(fh);
      const std::array<int, 3> key{c[0], c[1], c[2]};
      auto it = material_of_colour.find(key);
      if (it == material_of_colour.end()) {
        Material m;
        m.name = "ply_" + std::to_string(key[0]) + "_" + std::to_string(key[1]) + "_" + std::to_string(key[2]);
        m.Kd = Rgb(key[0], key[1], key[2]) / 255.0;
        it = material_of_colour.emplace(key, static_cast<int>(mesh.materials.size())).first;
        mesh.materials.push_back(m);
      }
      material = it->second;
    }
    mesh.face_material.push_back(material);
  }
  return mesh;
}

}  // namespace radwalk
