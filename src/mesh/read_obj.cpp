#include "mesh/read_obj.h"

#include <sys/stat.h>

#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include "core/error.h"
#include "core/excerpt.h"
#include "core/format_number.h"
#include "mesh/mtl.h"
#include "mesh/polygon_faces.h"
#include "mesh/text_scan.h"
#include "mesh/texture_mean.h"

namespace radwalk {

namespace {

struct ScannedFace {
  long line = 0;
  std::vector<std::int32_t> v;  // 0-based vertex indices (may be out of range; validate_mesh reports that)
  int usemtl = -1;              // index into ObjScan::usemtl, -1 before any usemtl
  std::int32_t group = -1;      // index into ObjScan::groups, -1 before any o or g
  std::string bad_index;        // why a corner's index is refused ("" if none): reported with the other findings
};

struct NamedLine {
  std::string name;
  long line = 0;
};

struct ObjScan {
  std::vector<Vec3> vertices;
  std::vector<ScannedFace> faces;
  std::vector<NamedLine> usemtl;
  std::vector<NamedLine> mtllib;
  std::vector<std::string> groups;  // "object 'o', group 'g'" labels in order of first use
  std::vector<std::string> group_object, group_name;  // their parts
  std::vector<NamedLine> bad_vertices;  // why a `v` statement cannot be read, and its line
  long ignored_elements = 0;  // `l` and `p` statements
  long first_ignored_line = 0;
  bool written_by_radwalk = false;  // the first line starts with kObjRadwalkHeader
  bool as_written_line = false;     // a line starts with kObjAsWrittenComment
  struct PairLine {
    long line = 0;
    std::optional<long> a, b;  // the face numbers declared (1-based), when they are numbers
  };
  std::vector<PairLine> contact_pairs;  // kObjContactPairComment lines, in order
};

// The parser: one pass over the statements, exact coordinates and strict checks (see read_obj.h).
ObjScan scan_obj(const std::string& path, std::string_view text) {
  ObjScan s;
  std::string object, group_name;  // the current o and g names
  std::int32_t group = -1;
  for_each_line(text, [&](long line, std::string_view content) {
    if (line == 1 && content.substr(0, kObjRadwalkHeader.size()) == kObjRadwalkHeader) s.written_by_radwalk = true;
    if (content.substr(0, kObjAsWrittenComment.size()) == kObjAsWrittenComment) {
      s.as_written_line = true;
      return;
    }
    if (content.substr(0, kObjContactPairComment.size()) == kObjContactPairComment) {
      const auto numbers = split_tokens(content.substr(kObjContactPairComment.size()));
      ObjScan::PairLine pair;
      pair.line = line;
      if (numbers.size() == 2) pair.a = parse_long(numbers[0]), pair.b = parse_long(numbers[1]);
      s.contact_pairs.push_back(pair);
      return;
    }
    const auto tokens = split_tokens(content);
    if (tokens.empty()) return;
    const std::string_view key = tokens[0];
    if (key == "v") {
      const std::size_t n = tokens.size() - 1;
      const std::string vertex = "vertex " + std::to_string(s.vertices.size() + 1);
      // A vertex that cannot be read is an error finding and a NaN vertex (the numbering of the others is kept;
      // validate_mesh refuses the faces that use it), so the rest of the file is still read and checked.
      Vec3 p = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
      if (n != 3 && n != 4 && n != 6 && n != 7) {
        s.bad_vertices.push_back({vertex + " has " + std::to_string(n) + " numbers, expected x y z (truncated line?)", line});
        s.vertices.push_back(p);
        return;
      }
      for (int k = 0; k < 3; ++k) {
        const auto x = parse_double(tokens[k + 1]);
        if (!x) {
          s.bad_vertices.push_back({vertex + ": '" + excerpt(tokens[k + 1]) + "' is not a number", line});
          p = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
          break;
        }
        // A non-finite coordinate (nan, inf) is kept: validate_mesh refuses the faces that use it, with the
        // scene's other findings.
        p[k] = *x;
      }
      s.vertices.push_back(p);
    } else if (key == "f") {
      const std::size_t n = tokens.size() - 1;
      // Fewer than 3 corners (`f a b`, an exporter's line segment) is not refused here: PolygonFaces drops the
      // face with a finding, after every other line is read.
      ScannedFace f;
      f.line = line;
      f.usemtl = static_cast<int>(s.usemtl.size()) - 1;
      f.group = group;
      for (std::size_t k = 1; k <= n; ++k) {
        const std::string_view token = tokens[k];
        const auto index = parse_long(token.substr(0, token.find('/')));
        if (!index) {
          if (f.bad_index.empty()) f.bad_index = "'" + excerpt(token) + "' is not a vertex index";
          continue;
        }
        const long resolved = *index > 0 ? *index - 1 : static_cast<long>(s.vertices.size()) + *index;
        if (f.bad_index.empty()) {
          if (*index == 0)
            f.bad_index = "vertex index 0 is invalid (OBJ counts from 1)";
          else if (resolved < 0)
            f.bad_index = "relative vertex index " + std::to_string(*index) + " points before the first vertex";
          else if (resolved > std::numeric_limits<std::int32_t>::max())
            f.bad_index = "vertex index " + std::to_string(*index) + " is too large";
        }
        if (!f.bad_index.empty()) continue;
        f.v.push_back(static_cast<std::int32_t>(resolved));
      }
      s.faces.push_back(std::move(f));
    } else if (key == "usemtl") {
      if (tokens.size() < 2) throw InputError(locate(path, line, -1, "usemtl without a material name"));
      s.usemtl.push_back({std::string(rest_of_statement(content, tokens[1])), line});
    } else if (key == "mtllib") {
      if (tokens.size() < 2) throw InputError(locate(path, line, -1, "mtllib without a file name"));
      s.mtllib.push_back({std::string(rest_of_statement(content, tokens[1])), line});
    } else if (key == "o" || key == "g") {
      // o NAME starts an object (and leaves its groups); g NAME ... sets the group(s) within it.
      const std::string name = tokens.size() >= 2 ? std::string(rest_of_statement(content, tokens[1])) : "";
      if (key == "o") {
        object = name;
        group_name.clear();
      } else {
        group_name = name;
      }
      std::string label;
      if (!object.empty()) label = "object '" + object + "'";
      if (!group_name.empty()) label += (label.empty() ? "" : ", ") + ("group '" + group_name + "'");
      group = -1;
      if (!label.empty()) {
        for (std::size_t k = 0; k < s.groups.size() && group < 0; ++k)
          if (s.groups[k] == label) group = static_cast<std::int32_t>(k);
        if (group < 0) {
          group = static_cast<std::int32_t>(s.groups.size());
          s.groups.push_back(label);
          s.group_object.push_back(object);
          s.group_name.push_back(group_name);
        }
      }
    } else if (key == "l" || key == "p") {
      if (s.ignored_elements++ == 0) s.first_ignored_line = line;
    }
  });
  return s;
}

// "a\ b" -> "a b": a space escaped with a backslash is part of a file name.
std::string unescape_spaces(std::string_view name) {
  std::string out;
  for (std::size_t k = 0; k < name.size(); ++k) {
    if (name[k] == '\\' && k + 1 < name.size() && (name[k + 1] == ' ' || name[k + 1] == '\t')) ++k;
    out.push_back(name[k]);
  }
  return out;
}

bool is_regular_file(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

// The files an mtllib statement names, resolved against the OBJ's directory (absolute paths as given). The
// whole rest of the statement is one file name if such a file exists (names with spaces, as some exporters write
// them); otherwise it is a list of file names separated by spaces or tabs, every one of which must exist.
std::vector<std::string> resolve_mtllib(const std::string& path, const NamedLine& lib, const std::string& dir,
                                        const MtlSource& source) {
  auto resolved = [&](const std::string& name) { return !name.empty() && name[0] == '/' ? name : dir + name; };
  const std::string whole = resolved(unescape_spaces(lib.name));
  if (source.exists(whole)) return {whole};
  std::vector<std::string> files;
  std::string name;
  auto add = [&] {
    if (name.empty()) return;
    const std::string file = resolved(name);
    if (!source.exists(file))
      throw InputError(locate(path, lib.line, -1, "material library '" + excerpt(name) + "' not found (looked for " +
                                                      printable(file) + ")"));
    files.push_back(file);
    name.clear();
  };
  for (std::size_t k = 0; k < lib.name.size(); ++k) {
    const char c = lib.name[k];
    if (c == '\\' && k + 1 < lib.name.size() && (lib.name[k + 1] == ' ' || lib.name[k + 1] == '\t')) {
      name.push_back(lib.name[++k]);
    } else if (c == ' ' || c == '\t') {
      add();
    } else {
      name.push_back(c);
    }
  }
  add();
  return files;
}

// Kd with a map_Kd texture (mtl.h, "Textures"): Kd (1 if the block has none) times the texture's mean linear
// colour (texture_mean.h), or times 0.5 when the texture cannot be read; a warning finding either way.
void apply_texture(Mesh& mesh, const MtlEntry& e, const MtlSource& source) {
  Material& m = mesh.materials.back();
  const std::string name = unescape_spaces(*e.map_Kd);
  const std::string file = !name.empty() && name[0] == '/' ? name : directory_of(e.file) + name;
  const Rgb Kd = e.Kd ? *e.Kd : Rgb::Ones();
  TextureMean t;
  bool found = false;
  try {
    found = source.exists(file);
    if (found) t = texture_mean(source.read(file));
  } catch (const InputError& error) {
    t.why = error.what();
  }
  Finding finding = mesh.finding_of(-1, 0, -1, -1, "texture", Severity::warning, "");
  finding.file = e.file;
  finding.line = e.map_Kd_line;
  finding.material = e.name;
  const std::string what =
      "material '" + excerpt(e.name) + "': Kd " + format_rgb(Kd, 4) + " with texture '" + excerpt(name) + "'";
  if (t.mean) {
    m.Kd = Kd * *t.mean;
    m.texture = file;
    finding.kind = "texture mean colour used";
    finding.message = what + ": rho = Kd times the texture's mean colour " + format_rgb(*t.mean, 4) +
                      " (linear, " + std::to_string(t.width) + " x " + std::to_string(t.height) +
                      " pixels) = " + format_rgb(m.Kd, 4) +
                      " (the radiosity solvers take one rho per material; --set '" + excerpt(e.name) +
                      ".Kd=r,g,b' sets another)";
  } else {
    m.Kd = 0.5 * Kd;
    finding.kind = "texture not read";
    finding.message =
        what +
        (found ? " that cannot be read (" + t.why + ")" : " not found (looked for " + printable(file) + ")") +
        ": rho = Kd times 0.5, radwalk's default reflectance, = " + format_rgb(m.Kd, 4) + "; --set '" +
        excerpt(e.name) + ".Kd=r,g,b' sets the texture's colour";
  }
  mesh.findings.push_back(finding);
}

}  // namespace

MtlSource mtl_files_on_disk() {
  return {is_regular_file, [](const std::string& file) { return read_input_file(file); }};
}

Mesh read_obj(const std::string& path, const ReadOptions& options) {
  return read_obj_text(path, read_input_file(path), mtl_files_on_disk(), options);
}

Mesh read_obj_text(const std::string& path, std::string_view text, const MtlSource& source,
                   const ReadOptions& options) {
  const ObjScan scan = scan_obj(path, text);
  const std::string dir = directory_of(path);

  // Material libraries: every listed file must exist; each is read once, in statement order.
  std::vector<MtlEntry> entries;
  std::vector<std::string> libraries;
  for (const auto& lib : scan.mtllib)
    for (const std::string& file : resolve_mtllib(path, lib, dir, source)) {
      bool seen = false;
      for (const auto& l : libraries) seen = seen || l == file;
      if (seen) continue;
      libraries.push_back(file);
      auto more = scan_mtl_text(file, source.read(file));
      entries.insert(entries.end(), more.begin(), more.end());
    }

  Mesh mesh;
  mesh.path = path;
  mesh.vertices = scan.vertices;
  for (const NamedLine& bad : scan.bad_vertices)
    mesh.findings.push_back(mesh.finding_of(-1, bad.line, -1, -1, "unreadable vertex", Severity::error, bad.name));

  // Materials: the first definition of a name wins; later ones are reported.
  std::map<std::string, int> by_name;
  for (const auto& e : entries) {
    const int index = static_cast<int>(mesh.materials.size());
    mesh.materials.push_back(material_from_mtl(e));
    if (e.map_Kd) apply_texture(mesh, e, source);
    if (!by_name.emplace(e.name, index).second)
    {
      Finding again = mesh.finding_of(-1, 0, -1, -1, "material defined again", Severity::warning,
                                      "material '" + excerpt(e.name) +
                                          "' is defined again; the first definition is used");
      again.file = e.file;
      again.line = e.line;
      mesh.findings.push_back(again);
    }
  }

  // Faces, with their lines, groups and materials; polygons of more than 4 corners triangulated (polygon_faces.h).
  const std::size_t n_faces = scan.faces.size();
  if (n_faces > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    throw InputError(locate(path, 0, -1, "too many faces"));
  mesh.groups = scan.groups;
  mesh.group_object = scan.group_object;
  mesh.group_name = scan.group_name;
  PolygonFaces faces(mesh, options.strict);
  // Materials that usemtl names but no library defines (given the default unless strict): the material, its first
  // face and usemtl statement, and how many faces use it.
  struct MissingMaterial {
    int material;
    std::size_t first_face;
    std::int32_t usemtl;
    std::size_t faces;
  };
  std::vector<MissingMaterial> missing;
  for (std::size_t f = 0; f < n_faces; ++f) {
    const ScannedFace& sf = scan.faces[f];
    std::int32_t material = -1;
    bool refused = false;
    if (sf.usemtl >= 0) {
      const NamedLine& use = scan.usemtl[static_cast<std::size_t>(sf.usemtl)];
      auto it = by_name.find(use.name);
      if (it == by_name.end() && !options.strict) {
        // Not in any library: the faces get the default material (rho 0.5, no emission, as a face without
        // material) under the name they use, so that --set NAME.Kd=r,g,b reaches them; one warning per name.
        Material d;
        d.name = use.name;
        d.Kd = Rgb::Constant(0.5);
        const int index = static_cast<int>(mesh.materials.size());
        mesh.materials.push_back(d);
        it = by_name.emplace(use.name, index).first;
        missing.push_back({index, f, sf.usemtl, 0});
      }
      if (it != by_name.end())
        for (MissingMaterial& m : missing)
          if (m.material == it->second) ++m.faces;
      if (it == by_name.end()) {
        std::string where = libraries.empty() ? std::string("no mtllib statement") : "not in ";
        for (std::size_t l = 0; l < libraries.size(); ++l) where += (l ? ", " : "") + libraries[l];
        Finding unknown = mesh.finding_of(static_cast<long>(f), sf.line, -1, sf.group, "unknown material",
                                          Severity::error,
                                          "unknown material '" + excerpt(use.name) + "' (usemtl at line " +
                                              std::to_string(use.line) + ": " + where + ")");
        unknown.material = use.name;
        mesh.findings.push_back(unknown);
        refused = true;
      } else {
        material = it->second;
      }
    }
    if (!sf.bad_index.empty()) {
      mesh.findings.push_back(mesh.finding_of(static_cast<long>(f), sf.line, material, sf.group, "bad vertex index",
                                              Severity::error, sf.bad_index));
      refused = true;
    }
    // A refused face is left out (the scene is refused after validation, with every finding).
    if (refused) continue;
    faces.add(sf.v, sf.line, material, sf.group, static_cast<std::int32_t>(f));
  }

  for (const MissingMaterial& m : missing) {
    const NamedLine& use = scan.usemtl[static_cast<std::size_t>(m.usemtl)];
    std::string where = libraries.empty() ? std::string("no mtllib statement") : "not in ";
    for (std::size_t l = 0; l < libraries.size(); ++l) where += (l ? ", " : "") + libraries[l];
    const ScannedFace& first = scan.faces[m.first_face];
    Finding given = mesh.finding_of(static_cast<long>(m.first_face), use.line, m.material, first.group,
                                    "unknown material given the default", Severity::repair,
                                    "unknown material '" + excerpt(use.name) + "' (usemtl at line " +
                                        std::to_string(use.line) + ": " + where + "): its " +
                                        std::to_string(m.faces) + (m.faces == 1 ? " face gets" : " faces get") +
                                        " the default material (rho 0.5, no emission) under that name; --set '" +
                                        excerpt(use.name) + ".Kd=r,g,b' sets it (--strict refuses it)");
    given.material = use.name;
    mesh.findings.push_back(given);
  }

  // A run's patches as radwalk wrote them (read_obj.h): validation keeps their orientation and sides.
  mesh.as_written = scan.written_by_radwalk && scan.as_written_line;

  if (scan.written_by_radwalk && !scan.contact_pairs.empty()) {
    // The contact pairs radwalk's writer names (read_obj.h): each face in one declaration at most.
    std::vector<int> declared(n_faces, 0);
    const auto face_of = [&](const std::optional<long>& number) -> long {
      return number && *number >= 1 && static_cast<std::size_t>(*number) <= n_faces ? *number - 1 : -1;
    };
    for (const auto& pair : scan.contact_pairs) {
      const long a = face_of(pair.a), b = face_of(pair.b);
      if (a >= 0) ++declared[static_cast<std::size_t>(a)];
      if (b >= 0 && b != a) ++declared[static_cast<std::size_t>(b)];
    }
    std::int32_t id = 0;
    for (const auto& pair : scan.contact_pairs) {
      const long a = face_of(pair.a), b = face_of(pair.b);
      if (a < 0 || b < 0 || a == b || declared[static_cast<std::size_t>(a)] != 1 ||
          declared[static_cast<std::size_t>(b)] != 1) {
        mesh.findings.push_back(mesh.finding_of(
            -1, pair.line, -1, -1, "contact pair declaration ignored", Severity::warning,
            "'" + std::string(kObjContactPairComment) + " A B' needs two different face numbers of the file (1 to " +
                std::to_string(n_faces) + "), each in one such line only: not used (the two faces, if they lie "
                                          "back to back, become one two-sided face)"));
        continue;
      }
      mesh.source_contact_pair.resize(n_faces, -1);
      mesh.source_contact_pair[static_cast<std::size_t>(a)] = id;
      mesh.source_contact_pair[static_cast<std::size_t>(b)] = id;
      ++id;
    }
  }

  if (scan.ignored_elements > 0)
    mesh.findings.push_back(mesh.finding_of(-1, scan.first_ignored_line, -1, -1, "line and point elements ignored",
                                            Severity::warning,
                                            std::to_string(scan.ignored_elements) +
                                                " line/point elements (l, p) ignored: radiosity needs surfaces"));
  return mesh;
}

}  // namespace radwalk
