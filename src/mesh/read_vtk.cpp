#include "mesh/read_vtk.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <optional>
#include <string_view>
#include <cctype>
#include <tuple>
#include <vector>

#include "core/error.h"
#include "core/excerpt.h"
#include "mesh/exact_vertices.h"
#include "mesh/polygon_faces.h"
#include "mesh/text_scan.h"
#include "mesh/triangulate.h"
#include "mesh/vtk_data_array.h"
#include "mesh/vtk_legacy.h"
#include "mesh/vtp_xml.h"

namespace radwalk {
namespace {

// What radwalk takes from a polygonal data set, whichever reader read it: the points, the surface cells (polygons
// and triangle strips, each a run of point ids) in cell-data order, and the cell and field data it uses.
struct SurfaceData {
  std::vector<Vec3> points;
  std::size_t cells = 0;  // every cell, vertices and lines included: the length of a cell data array
  std::size_t ignored = 0;  // vertex and line cells
  struct Cell {
    std::size_t index;       // its place in the cell data
    bool strip;
    std::size_t begin, end;  // its point ids: ids[begin, end)
  };
  std::vector<Cell> surface;
  std::vector<std::int32_t> ids;
  // The cell data arrays by name (3 components for rho and E, 1 for the others), each of `cells` tuples.
  std::map<std::string, std::vector<double>> cell_data;
  std::map<std::string, std::vector<std::string>> tables;  // field data string arrays by name
};

// The cell and field data radwalk uses (read_vtk.h), and their component counts.
const std::pair<const char*, int> kCellFields[] = {{"rho", 3},         {"E", 3},          {"side", 1},
                                                   {"material_id", 1}, {"group_id", 1},   {"object_id", 1},
                                                   {"patch", 1},       {"face", 1},       {"contact_pair", 1}};
const char* const kTables[] = {"material_names", "group_names", "object_names"};

// --- legacy .vtk: radwalk's own reader (vtk_legacy.h) ----------------------------------------------------------

SurfaceData legacy_surface(const std::string& path, std::string_view bytes) {
  LegacyWanted wanted;
  for (const auto& [name, components] : kCellFields) wanted.cell_arrays.emplace(name, components);
  for (const char* name : kTables) wanted.field_strings.emplace_back(name);
  LegacyPolyData data = parse_vtk_legacy(path, bytes, wanted);
  SurfaceData s;
  s.points = std::move(data.points);
  s.cells = data.verts.count() + data.lines.count() + data.polys.count() + data.strips.count();
  s.ignored = data.verts.count() + data.lines.count();
  std::size_t cell = s.ignored;  // cell data order: vertices, lines, polygons, strips
  long face = 0;
  for (const bool strip : {false, true}) {
    const LegacyCells& cells = strip ? data.strips : data.polys;
    for (std::size_t c = 0; c < cells.count(); ++c, ++cell) {
      const auto begin = static_cast<std::size_t>(cells.offsets[c]), end = static_cast<std::size_t>(cells.offsets[c + 1]);
      if (!strip && end - begin > kMaxPolygonCorners)
        throw InputError(locate(path, 0, face, "polygon of " + std::to_string(end - begin) + " corners, more than " +
                                                   std::to_string(kMaxPolygonCorners)));
      const std::size_t first = s.ids.size();
      s.ids.insert(s.ids.end(), cells.ids.begin() + static_cast<std::ptrdiff_t>(begin),
                   cells.ids.begin() + static_cast<std::ptrdiff_t>(end));
      face += strip ? std::max<long>(0, static_cast<long>(end - begin) - 2) : 1;
      s.surface.push_back({cell, strip, first, s.ids.size()});
    }
  }
  s.cell_data = std::move(data.cell_data);
  s.tables = std::move(data.field_strings);
  return s;
}

// --- XML .vtp: radwalk's own reader (vtp_xml.h, vtk_data_array.h) ------------------------------------------------

// The cells of one kind of a piece (`count` of them, its NumberOf... attribute): the runs of its connectivity
// between consecutive offsets (offsets are each cell's end; they rise from 0 to the connectivity's length), every
// point id below `points`. Appends the ids, plus `first_id` (the points of the pieces before), to `all_ids` and
// returns each cell's [begin, end) in it.
std::vector<std::pair<std::size_t, std::size_t>> piece_cells(const std::string& path, const VtpDocument& doc,
                                                             const VtpCells& cells, const char* kind,
                                                             std::int64_t count, std::int64_t points,
                                                             std::int64_t first_id, long piece_line,
                                                             std::vector<std::int32_t>& all_ids) {
  std::vector<std::pair<std::size_t, std::size_t>> out;
  if (count == 0) return out;
  if (!cells.present)
    throw InputError(locate(path, piece_line, -1, "Piece declares " + std::to_string(count) + " " + kind +
                                                      " but has no <" + kind + "> element"));
  const VtpArray* connectivity = nullptr;
  const VtpArray* offsets = nullptr;
  for (const VtpArray& a : cells.arrays) {
    if (a.name == "connectivity" && !connectivity) connectivity = &a;
    if (a.name == "offsets" && !offsets) offsets = &a;
  }
  if (!connectivity || !offsets)
    throw InputError(locate(path, cells.line, -1, std::string(kind) + " without a" +
                                                      (connectivity ? "n offsets" : " connectivity") + " array"));
  for (const VtpArray* a : {connectivity, offsets}) {
    if (a->type == "Float32" || a->type == "Float64" || a->type == "String")
      throw InputError(locate(path, a->line, -1, std::string(kind) + " " + array_label(*a) + " of type " + a->type +
                                                     ": cell arrays hold whole numbers"));
    if (a->components != 1)
      throw InputError(locate(path, a->line, -1, std::string(kind) + " " + array_label(*a) + " of " +
                                                     std::to_string(a->components) + " components, not 1"));
  }
  const std::vector<double> ends = decode_numbers(path, doc, *offsets, count);
  const std::vector<double> ids = decode_numbers(path, doc, *connectivity, -1);
  double previous = 0;
  for (std::size_t c = 0; c < ends.size(); ++c) {
    if (!(ends[c] >= previous && ends[c] <= static_cast<double>(ids.size())))
      throw InputError(locate(path, offsets->line, -1,
                              std::string(kind) + " offsets: offset " + number_text(ends[c]) + " of cell " +
                                  std::to_string(c) + " is not between the previous offset " + number_text(previous) +
                                  " and the connectivity's " + std::to_string(ids.size()) + " ids"));
    previous = ends[c];
  }
  if (previous != static_cast<double>(ids.size()))
    throw InputError(locate(path, offsets->line, -1, std::string(kind) + " offsets end at " + number_text(previous) +
                                                         ", not at the connectivity's " + std::to_string(ids.size()) +
                                                         " ids"));
  std::size_t at = 0;
  out.reserve(ends.size());
  for (std::size_t c = 0; c < ends.size(); ++c) {
    const auto end = static_cast<std::size_t>(ends[c]);
    if (std::string_view(kind) == "Polys" && end - at > kMaxPolygonCorners)
      throw InputError(locate(path, offsets->line, -1, "Polys: polygon " + std::to_string(c) + " of " +
                                                           std::to_string(end - at) + " corners, more than " +
                                                           std::to_string(kMaxPolygonCorners)));
    const std::size_t begin = all_ids.size();
    for (; at < end; ++at) {
      const double id = ids[at];
      if (!(id >= 0 && id < static_cast<double>(points)))
        throw InputError(locate(path, connectivity->line, -1,
                                std::string(kind) + " connectivity: point id " + number_text(id) + " of cell " +
                                    std::to_string(c) + " is out of range (" + std::to_string(points) + " points)"));
      all_ids.push_back(static_cast<std::int32_t>(first_id + static_cast<std::int64_t>(id)));
    }
    out.emplace_back(begin, all_ids.size());
  }
  return out;
}

SurfaceData xml_surface(const std::string& path, std::string_view bytes) {
  const VtpDocument doc = parse_vtp_document(path, bytes);
  SurfaceData s;
  std::map<std::string, std::size_t> pieces_with;  // cell data arrays: the pieces that have each (of the right shape)
  std::int64_t total_points = 0;
  for (const VtpPiece& piece : doc.pieces) {
    if (piece.points > std::numeric_limits<std::int32_t>::max() / 2 - total_points)
      throw InputError(locate(path, piece.line, -1, "too many points"));
    const std::size_t first_cell = s.cells;
    // Each point (3 values) and each cell (its offset) takes at least a byte, or 1/1032 of one compressed: a count
    // above that is refused before anything is sized by it (and the sums below cannot overflow).
    const double most = (doc.compressed ? kZlibLargestRatio : 1.0) * static_cast<double>(bytes.size());
    for (const auto& [what, n] : {std::make_pair("points", piece.points), std::make_pair("vertex cells", piece.verts),
                                  std::make_pair("line cells", piece.lines), std::make_pair("strips", piece.strips),
                                  std::make_pair("polygons", piece.polys)})
      if (static_cast<double>(n) > most)
        throw InputError(locate(path, piece.line, -1, "Piece declares " + std::to_string(n) + " " + what +
                                                          ", more than its " + std::to_string(bytes.size()) +
                                                          " bytes can hold (truncated file or wrong count)"));
    const std::int64_t cells = piece.verts + piece.lines + piece.strips + piece.polys;
    if (piece.points > 0) {
      if (!piece.has_points)
        throw InputError(locate(path, piece.line, -1, "Piece declares " + std::to_string(piece.points) +
                                                          " points but has no <Points> DataArray"));
      const VtpArray& a = piece.point_coordinates;
      if (a.components != 3)
        throw InputError(locate(path, a.line, -1, "Points " + array_label(a) + " of " +
                                                      std::to_string(a.components) + " components, not 3"));
      const std::vector<double> xyz = decode_numbers(path, doc, a, 3 * piece.points);
      for (std::size_t k = 0; k + 2 < xyz.size(); k += 3) s.points.emplace_back(xyz[k], xyz[k + 1], xyz[k + 2]);
    }
    // Cell order within a piece, as VTK numbers cells: vertices, lines, polygons, strips.
    // Vertices and lines are checked, then forgotten (their ids are not kept).
    std::vector<std::int32_t> ignored_ids;
    const auto verts = piece_cells(path, doc, piece.verts_cells, "Verts", piece.verts, piece.points, total_points,
                                   piece.line, ignored_ids);
    const auto lines = piece_cells(path, doc, piece.lines_cells, "Lines", piece.lines, piece.points, total_points,
                                   piece.line, ignored_ids);
    s.ignored += verts.size() + lines.size();
    std::size_t cell = first_cell + verts.size() + lines.size();
    for (const bool strip : {false, true}) {
      const auto runs = piece_cells(path, doc, strip ? piece.strips_cells : piece.polys_cells,
                                    strip ? "Strips" : "Polys", strip ? piece.strips : piece.polys, piece.points,
                                    total_points, piece.line, s.ids);
      for (const auto& [begin, end] : runs) s.surface.push_back({cell++, strip, begin, end});
    }
    s.cells = cell;
    total_points += piece.points;
    // The cell data radwalk uses: by name, of the right component count and a numeric type (else not used, as
    // before); its values must be there, one tuple per cell.
    for (const auto& [name, components] : kCellFields) {
      for (const VtpArray& a : piece.cell_data) {
        if (a.name != name || a.components != components || a.type == "String") continue;
        std::vector<double> values = decode_numbers(path, doc, a, cells * components);
        std::vector<double>& all = s.cell_data[name];
        all.resize(first_cell * static_cast<std::size_t>(components));  // pieces before without it: filled later
        all.insert(all.end(), values.begin(), values.end());
        ++pieces_with[name];
        break;
      }
    }
  }
  // A cell data array used only when every piece has it.
  for (auto it = s.cell_data.begin(); it != s.cell_data.end();)
    it = pieces_with[it->first] == doc.pieces.size() ? std::next(it) : s.cell_data.erase(it);
  for (const char* name : kTables)
    for (const VtpArray& a : doc.field_data)
      if (a.name == name && a.type == "String") {
        s.tables[name] = decode_strings(path, doc, a);
        break;
      }
  return s;
}

// Drops corners on the segment between their neighbours (see read_vtk.h), keeping at least 3.
std::vector<std::int32_t> without_straight_corners(const std::vector<std::int32_t>& corners,
                                                   const std::vector<Vec3>& points) {
  std::vector<std::int32_t> kept = corners;
  bool dropped = true;
  while (dropped && kept.size() > 3) {
    dropped = false;
    for (std::size_t k = 0; k < kept.size() && kept.size() > 3; ++k) {
      const Vec3& a = points[static_cast<std::size_t>(kept[(k + kept.size() - 1) % kept.size()])];
      const Vec3& b = points[static_cast<std::size_t>(kept[k])];
      const Vec3& c = points[static_cast<std::size_t>(kept[(k + 1) % kept.size()])];
      const Vec3 u = b - a, v = c - b;
      if (u.cross(v).norm() <= 1e-12 * u.norm() * v.norm() && u.dot(v) > 0) {
        kept.erase(kept.begin() + static_cast<std::ptrdiff_t>(k));
        dropped = true;
        break;
      }
    }
  }
  return kept;
}

// Whether the file is radwalk's own .vtp as written: its cell fields `patch` and `face` are there (the fields of
// every radwalk patch output, io/cell_field.h) and `patch` numbers the cells 0, 1, ... in order (a file whose cells
// were removed or reordered since, or another program's, is read as any other).
bool written_by_radwalk(const SurfaceData& data, const std::vector<double>* patch, const std::vector<double>* face) {
  if (!patch || !face || data.ignored > 0) return false;
  for (std::size_t cell = 0; cell < data.cells; ++cell)
    if ((*patch)[cell] != static_cast<double>(cell)) return false;
  return true;
}

// The contact pairs a file declares, per cell (its pair id, -1 for none; empty when it declares none): only in
// radwalk's own file as written (written_by_radwalk), and only ids held by exactly two polygon cells that are
// fronts (not `side` 1), as patch/contact_pairs.h makes them; other ids are not used.
std::vector<std::int32_t> declared_contact_pairs(const SurfaceData& data, bool own, const std::vector<double>* pair,
                                                 const std::vector<double>* side) {
  if (!own || !pair) return {};
  std::vector<std::int32_t> pair_of(data.cells, -1);
  std::map<std::int32_t, int> members;
  for (const SurfaceData::Cell& c : data.surface) {
    const double id = (*pair)[c.index];
    if (c.strip || (side && (*side)[c.index] == 1) || !(id >= 0 && id <= std::numeric_limits<std::int32_t>::max()) ||
        id != std::floor(id))
      continue;
    pair_of[c.index] = static_cast<std::int32_t>(id);
    ++members[pair_of[c.index]];
  }
  for (std::int32_t& id : pair_of)
    if (id >= 0 && members[id] != 2) id = -1;
  return pair_of;
}

}  // namespace

Mesh read_vtk_polydata(const std::string& path, const ReadOptions& options) {
  const std::string ext = lower_extension(path);
  return read_vtk_polydata_bytes(path, read_input_file(path), ext == "vtp", options);
}

Mesh read_vtk_polydata_bytes(const std::string& path, std::string_view bytes, bool xml, const ReadOptions& options) {
  const SurfaceData data = xml ? xml_surface(path, bytes) : legacy_surface(path, bytes);
  Mesh mesh;
  mesh.path = path;
  const std::vector<Vec3>& points = data.points;
  std::vector<std::int32_t> vertex_of(points.size());
  ExactVertices vertices(mesh.vertices);
  for (std::size_t k = 0; k < points.size(); ++k) vertex_of[k] = vertices.index(points[k]);
  if (data.surface.empty()) throw InputError(locate(path, 0, -1, "no polygons or triangle strips"));
  if (data.ignored > 0)
    mesh.findings.push_back(mesh.finding_of(-1, 0, -1, -1, "line and point elements ignored", Severity::warning,
                                            std::to_string(data.ignored) +
                                                " vertex and line cells ignored: radiosity needs surfaces"));

  const auto field = [&](const char* name) -> const std::vector<double>* {
    const auto it = data.cell_data.find(name);
    return it == data.cell_data.end() ? nullptr : &it->second;
  };
  const std::vector<double>* rho = field("rho");
  const std::vector<double>* E = field("E");
  const std::vector<double>* side = field("side");
  const std::vector<double>* material_id = field("material_id");
  const std::vector<double>* group_id = field("group_id");
  const std::vector<double>* object_id = field("object_id");
  // rho and E are numbers: a value that is not finite is refused, naming its cell.
  for (const auto& [name, values] : {std::make_pair("rho", rho), std::make_pair("E", E)}) {
    if (!values) continue;
    for (std::size_t k = 0; k < values->size(); ++k)
      if (!std::isfinite((*values)[k]))
        throw InputError(locate(path, 0, -1, std::string("cell data '") + name + "' of cell " +
                                                 std::to_string(k / 3) + " is not finite (" +
                                                 number_text((*values)[k]) + ")"));
  }
  const auto table = [&](const char* name) {
    const auto it = data.tables.find(name);
    return it == data.tables.end() ? std::vector<std::string>() : it->second;
  };
  const std::vector<std::string> material_names = table("material_names");
  const std::vector<std::string> group_names = table("group_names");
  const std::vector<std::string> object_names = table("object_names");
  auto name_at = [](const std::vector<std::string>& names, const std::vector<double>* ids,
                    std::size_t cell) -> std::string {
    if (!ids) return "";
    const double id = (*ids)[cell];
    if (!(id >= 0 && id < static_cast<double>(names.size()))) return "";
    return names[static_cast<std::size_t>(id)];
  };

  // Materials: by (name, rho, E); see read_vtk.h.
  std::map<std::tuple<std::string, double, double, double, double, double, double>, std::int32_t> material_of;
  std::map<std::string, int> name_uses;
  auto material_for = [&](std::size_t cell) -> std::int32_t {
    Rgb kd = Rgb::Zero(), e = Rgb::Zero();
    for (int c = 0; c < 3; ++c) {
      if (rho) kd[c] = (*rho)[3 * cell + static_cast<std::size_t>(c)];
      if (E) e[c] = (*E)[3 * cell + static_cast<std::size_t>(c)];
    }
    std::string base = name_at(material_names, material_id, cell);
    if (!rho) base = std::filesystem::path(path).stem().string();
    const auto key = std::make_tuple(base, kd[0], kd[1], kd[2], e[0], e[1], e[2]);
    const auto it = material_of.find(key);
    if (it != material_of.end()) return it->second;
    Material m;
    if (base.empty()) {
      m.name = "vtk_material_" + std::to_string(material_of.size());
    } else {
      const int uses = ++name_uses[base];
      m.name = uses == 1 ? base : base + "_" + std::to_string(uses);
    }
    m.Kd = kd;
    m.Ke = e / kPi;
    m.reflectance_missing = rho == nullptr;
    const auto index = static_cast<std::int32_t>(mesh.materials.size());
    mesh.materials.push_back(m);
    material_of.emplace(key, index);
    return index;
  };
  std::map<std::pair<std::string, std::string>, std::int32_t> group_of;
  auto group_for = [&](std::size_t cell) -> std::int32_t {
    const std::string object = name_at(object_names, object_id, cell), group = name_at(group_names, group_id, cell);
    if (object.empty() && group.empty()) return -1;
    const auto [it, added] = group_of.emplace(std::make_pair(object, group), static_cast<std::int32_t>(mesh.groups.size()));
    if (added) {
      std::string label;
      if (!object.empty()) label = "object '" + object + "'";
      if (!group.empty()) label += (label.empty() ? "" : ", ") + ("group '" + group + "'");
      mesh.groups.push_back(label);
      mesh.group_object.push_back(object);
      mesh.group_name.push_back(group);
    }
    return it->second;
  };

  mesh.as_written = written_by_radwalk(data, field("patch"), field("face"));
  const std::vector<std::int32_t> pair_of = declared_contact_pairs(data, mesh.as_written, field("contact_pair"), side);

  // A back cell is read as its front's back (below), which holds only where the backs are tiled as their fronts
  // are; a hierarchical run refines the two sides of a two-sided face apart, and the contact cut cuts only the side
  // an object touches, so a run's backs may not be: said, once.
  std::optional<std::pair<long, std::size_t>> unmatched_back;  // (count, first cell)
  if (side) {
    const auto corner_set = [&](const SurfaceData::Cell& c) {
      std::vector<std::int32_t> ids;
      const std::vector<std::int32_t> cell(data.ids.begin() + std::ptrdiff_t(c.begin),
                                           data.ids.begin() + std::ptrdiff_t(c.end));
      for (const std::int32_t p : without_straight_corners(cell, points))
        ids.push_back(vertex_of[static_cast<std::size_t>(p)]);
      std::sort(ids.begin(), ids.end());
      return ids;
    };
    std::set<std::vector<std::int32_t>> fronts;
    for (const SurfaceData::Cell& c : data.surface)
      if (!c.strip && (*side)[c.index] != 1) fronts.insert(corner_set(c));
    for (const SurfaceData::Cell& c : data.surface) {
      if (c.strip || (*side)[c.index] != 1 || fronts.count(corner_set(c))) continue;
      if (!unmatched_back) unmatched_back = std::make_pair(0L, c.index);
      ++unmatched_back->first;
    }
  }

  PolygonFaces faces(mesh, options.strict);
  std::int32_t face = 0;
  auto add_cell = [&](std::size_t cell, const std::vector<std::int32_t>& point_ids) {
    const std::int32_t source = face++;
    if (side && (*side)[cell] == 1) {  // a back cell: its front stands for it
      mesh.materials[static_cast<std::size_t>(material_for(cell))].two_sided = true;
      return;
    }
    if (!pair_of.empty() && pair_of[cell] >= 0) {
      mesh.source_contact_pair.resize(static_cast<std::size_t>(source) + 1, -1);
      mesh.source_contact_pair[static_cast<std::size_t>(source)] = pair_of[cell];
    }
    const std::int32_t material = material_for(cell);  // two-sided only if a back cell has its material
    std::vector<std::int32_t> corners;
    for (const std::int32_t p : without_straight_corners(point_ids, points))
      corners.push_back(vertex_of[static_cast<std::size_t>(p)]);
    if (corners.size() < 3) {
      mesh.findings.push_back(mesh.finding_of(source, 0, material, group_for(cell), "face of fewer than 3 corners",
                                              Severity::error,
                                              "has " + std::to_string(corners.size()) +
                                                  " corners, a face needs at least 3"));
      return;
    }
    faces.add(corners, 0, material, group_for(cell), source);
  };
  for (const SurfaceData::Cell& c : data.surface) {
    const std::int32_t* ids = data.ids.data() + c.begin;
    const std::size_t n = c.end - c.begin;
    if (!c.strip) {
      add_cell(c.index, std::vector<std::int32_t>(ids, ids + n));
      continue;
    }
    for (std::size_t t = 0; t + 2 < n; ++t) {
      if (t % 2 == 0)
        add_cell(c.index, {ids[t], ids[t + 1], ids[t + 2]});
      else
        add_cell(c.index, {ids[t + 1], ids[t], ids[t + 2]});
    }
  }
  if (unmatched_back) {  // after the cells, so that the materials keep the order of their first cells
    const std::size_t first = unmatched_back->second;
    mesh.findings.push_back(mesh.finding_of(
        static_cast<long>(first), 0, material_for(first), group_for(first), "back cells tiled otherwise",
        Severity::warning,
        std::to_string(unmatched_back->first) + " back cells (side 1) are not the backs of front cells (the two "
        "sides of a two-sided face were patched apart: a hierarchical run refines them apart, the contact cut cuts "
        "the side an object touches): read with the fronts' cells on both sides, so these cells and their values "
        "are not used"));
  }
  return mesh;
}

}  // namespace radwalk
