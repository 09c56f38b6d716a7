#include "mesh/read_vtk.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <string_view>
#include <cctype>
#include <tuple>
#include <vector>

#include <vtkAbstractArray.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataReader.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>

#include "core/error.h"
#include "core/excerpt.h"
#include "mesh/exact_vertices.h"
#include "mesh/polygon_faces.h"
#include "mesh/text_scan.h"
#include "mesh/triangulate.h"
#include "mesh/vtk_data_array.h"
#include "mesh/vtp_xml.h"

namespace radwalk {
namespace {

// Collects what VTK prints while radwalk reads, instead of printing it: the first error becomes the refusal.
class CapturingOutputWindow : public vtkOutputWindow {
 public:
  static CapturingOutputWindow* New();
  vtkTypeMacro(CapturingOutputWindow, vtkOutputWindow)
  void DisplayText(const char* text) override { keep(text, false); }
  void DisplayErrorText(const char* text) override { keep(text, true); }
  void DisplayWarningText(const char*) override {}
  void DisplayGenericWarningText(const char*) override {}
  void DisplayDebugText(const char*) override {}
  const std::string& error() const { return error_; }

 private:
  // VTK's message is "ERROR: In FILE, line N\nCLASS (0x...): WHAT\n\n": WHAT is kept.
  void keep(const char* text, bool is_error) {
    if (!text || !error_.empty()) return;
    std::string t(text);
    if (!is_error && t.find("ERROR") == std::string::npos) return;
    std::string last;
    std::size_t start = 0;
    while (start <= t.size()) {
      const std::size_t end = t.find('\n', start);
      const std::string line = t.substr(start, end == std::string::npos ? std::string::npos : end - start);
      if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
      if (end == std::string::npos) break;
      start = end + 1;
    }
    const std::size_t colon = last.find("): ");
    if (colon != std::string::npos) last = last.substr(colon + 3);
    error_ = last.empty() ? "unreadable" : last;
  }
  std::string error_;
};
vtkStandardNewMacro(CapturingOutputWindow);

// Installs a CapturingOutputWindow for its lifetime, and keeps VTK's logger (which writes errors to stderr on its
// own) quiet meanwhile.
class CaptureScope {
 public:
  CaptureScope() : previous_(vtkOutputWindow::GetInstance()), verbosity_(vtkLogger::GetCurrentVerbosityCutoff()) {
    window_ = vtkSmartPointer<CapturingOutputWindow>::New();
    vtkOutputWindow::SetInstance(window_);
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  }
  ~CaptureScope() {
    vtkLogger::SetStderrVerbosity(verbosity_);
    vtkOutputWindow::SetInstance(previous_);
  }
  const std::string& error() const { return window_->error(); }

 private:
  vtkSmartPointer<vtkOutputWindow> previous_;
  vtkLogger::Verbosity verbosity_;
  vtkSmartPointer<CapturingOutputWindow> window_;
};

// The legacy keyword a token stands for, as VTK's legacy reader matches it: the token lowercased starts with the
// keyword (VTK compares the keyword's length only: "POLYGONS`1" is POLYGONS); "" for none.
std::string legacy_keyword(std::string_view token) {
  static const char* const kKeywords[] = {"POINTS",   "POLYGONS", "TRIANGLE_STRIPS", "VERTICES",  "LINES",
                                          "OFFSETS",  "CONNECTIVITY", "CELL_DATA", "POINT_DATA", "FIELD",
                                          "SCALARS", "COLOR_SCALARS"};
  for (const char* k : kKeywords) {
    const std::string_view key(k);
    if (token.size() < key.size()) continue;
    bool same = true;
    for (std::size_t i = 0; i < key.size() && same; ++i)
      same = std::toupper(static_cast<unsigned char>(token[i])) == key[i];
    if (same) return k;
  }
  return "";
}

// Whether `type` (after POINTS n) names a numeric type of VTK's legacy format, in any case as VTK lowercases it.
// VTK 9.1 matches the type by its prefix, so "stringdouble" was a string array of points, on which its legacy
// reader dereferenced a null pointer (found by the vtk fuzz harness): only the exact names are taken.
bool legacy_numeric_type(std::string_view type) {
  static const char* const kNumeric[] = {"unsigned_char", "char",          "signed_char", "unsigned_short",
                                         "short",         "unsigned_int",  "int",         "unsigned_long",
                                         "long",          "float",         "double",      "vtkidtype",
                                         "vtktypeint64",  "vtktypeuint64"};
  std::string lower(type);
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const char* t : kNumeric)
    if (lower == t) return true;
  return false;
}

[[noreturn]] void refuse_points_type(const std::string& path, long line, std::string_view type) {
  throw InputError(locate(path, line, -1, "POINTS of type '" + excerpt(type) +
                                              "': not one of VTK's numeric types (float, double, int, ...)"));
}

// The bound of read_vtk.h on the counts a legacy file declares, before VTK allocates anything.
void check_declared_counts(const std::string& path, std::string_view bytes) {
  const double size = static_cast<double>(bytes.size());
  double largest_count = 0, largest_components = 1;
  const std::string_view text = bytes;
  // The numbers after the keywords that size VTK's arrays.
  long line_number = 0;
  bool field_arrays = false;
  for_each_line(text, [&](long line, std::string_view content) {
    line_number = line;
    const auto tokens = split_tokens(content);
    if (tokens.empty()) return;
    const std::string key = legacy_keyword(tokens[0]);
    std::vector<double> counts;
    auto number = [&](std::size_t k) {
      if (k >= tokens.size()) return;
      const auto n = parse_double(tokens[k]);
      if (n && *n >= 0) counts.push_back(*n);
    };
    if (key == "POINTS" || key == "CELL_DATA" || key == "POINT_DATA") {
      number(1);
      if (key == "POINTS" && tokens.size() >= 3 && !legacy_numeric_type(tokens[2]))
        refuse_points_type(path, line, tokens[2]);
      field_arrays = false;
    } else if (key == "POLYGONS" || key == "TRIANGLE_STRIPS" || key == "VERTICES" || key == "LINES" ||
               key == "OFFSETS" || key == "CONNECTIVITY") {
      number(1);
      number(2);
      field_arrays = false;
    } else if (key == "FIELD") {
      number(2);
      field_arrays = true;
    } else if (field_arrays && tokens.size() == 4 && !parse_double(tokens[0])) {  // NAME COMPONENTS TUPLES TYPE
      const auto c = parse_double(tokens[1]), t = parse_double(tokens[2]);
      if (c && t && *c >= 0 && *t >= 0) counts.push_back(*c * *t);
    } else if ((key == "SCALARS" || key == "COLOR_SCALARS") && tokens.size() >= 3) {
      const auto c = parse_double(tokens[tokens.size() - 1]);
      if (c && *c >= 0) largest_components = std::max(largest_components, *c);
    }
    for (double n : counts)
      if (n > size)
        throw InputError(locate(path, line, -1, "declares " + number_text(n) + " items, more than its " +
                                                    std::to_string(bytes.size()) +
                                                    " bytes can hold (truncated file or wrong count)"));
    for (double n : counts) largest_count = std::max(largest_count, n);
  });
  if (largest_count * largest_components > 4 * size)
    throw InputError(locate(path, 0, -1, "declares " + number_text(largest_count) + " items of " +
                                             number_text(largest_components) + " components, more than its " +
                                             std::to_string(bytes.size()) + " bytes can hold"));
}

// An ASCII legacy file's geometry sections hold what their headers say, before VTK reads them: POINTS n TYPE is
// followed by 3 n numbers; POLYGONS, TRIANGLE_STRIPS, VERTICES and LINES n size by `size` whole numbers >= 0 (the
// format of version 5.1 instead by OFFSETS TYPE and CONNECTIVITY TYPE sections of whole numbers >= 0, of n and
// size). VTK 9.1's legacy reader, given a section whose numbers do not parse (a word among a polygon's indices),
// goes on reading the stream it closed and crashes (found by the vtk fuzz harness); the first section that is
// short or holds something else is refused here in one line naming its line. The header's first three lines (the
// version, the title, ASCII) are not sections.
void check_ascii_legacy_sections(const std::string& path, std::string_view bytes) {
  // The tokens as VTK's reader sees them: separated by white space, lines by '\n' (views into bytes).
  struct Token {
    std::string_view text;
    long line;
  };
  std::vector<Token> tokens;
  std::vector<std::string_view> third_line;
  long line_at = 1;
  for (std::size_t i = 0; i < bytes.size();) {
    const char c = bytes[i];
    if (c == '\n') {
      ++line_at;
      ++i;
      continue;
    }
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[j]))) ++j;
    if (line_at == 3) third_line.push_back(bytes.substr(i, j - i));
    if (line_at > 3) tokens.push_back({bytes.substr(i, j - i), line_at});
    i = j;
  }
  // VTK takes the file as ASCII when the third line starts with "ascii" in any case ("ASCII\\0" is ASCII).
  const auto ascii_word = [](std::string_view w) {
    if (w.size() < 5) return false;
    for (std::size_t i = 0; i < 5; ++i)
      if (std::tolower(static_cast<unsigned char>(w[i])) != "ascii"[i]) return false;
    return true;
  };
  if (third_line.empty() || !ascii_word(third_line[0])) return;
  std::size_t k = 0;
  // Requires `count` tokens after k of the kind `whole` (else numbers), naming `what` and the line of its header.
  auto require = [&](double count, bool whole, const std::string& what, long header_line) {
    for (double i = 0; i < count; ++i, ++k) {
      if (k >= tokens.size())
        throw InputError(locate(path, header_line, -1, what + " ends before its " + number_text(count) +
                                                           (whole ? " indices" : " numbers")));
      // VTK 9.1's legacy reader reads cell sections as 32-bit ints: a larger whole number made it fail, then
      // dereference a null pointer (found by the vtk fuzz harness).
      const long whole_value = whole ? parse_long(tokens[k].text).value_or(-1) : 0;
      const bool ok = whole ? whole_value >= 0 && whole_value <= std::numeric_limits<std::int32_t>::max()
                            : parse_double(tokens[k].text).has_value();
      if (!ok)
        throw InputError(locate(path, tokens[k].line, -1,
                                what + " (line " + std::to_string(header_line) + "): '" + excerpt(tokens[k].text) +
                                    "' is not " + (whole ? "a whole number from 0 to 2147483647" : "a number")));
    }
  };
  auto count_at = [&](std::size_t at) -> double {
    if (at >= tokens.size()) return -1;
    const auto n = parse_double(tokens[at].text);
    return n && *n >= 0 && *n == std::floor(*n) ? *n : -1;
  };
  while (k < tokens.size()) {
    const std::string key = legacy_keyword(tokens[k].text);
    const long line = tokens[k].line;
    if (key == "POINTS") {
      const double n = count_at(k + 1);
      if (n < 0) throw InputError(locate(path, line, -1, "POINTS needs a count"));
      if (k + 2 >= tokens.size() || !legacy_numeric_type(tokens[k + 2].text))
        refuse_points_type(path, line, k + 2 < tokens.size() ? tokens[k + 2].text : std::string_view());
      k += 3;  // POINTS n TYPE
      require(3 * n, false, "POINTS", line);
    } else if (key == "POLYGONS" || key == "TRIANGLE_STRIPS" || key == "VERTICES" || key == "LINES") {
      const double n = count_at(k + 1), size = count_at(k + 2);
      if (n < 0 || size < 0) throw InputError(locate(path, line, -1, std::string(key) + " needs two counts"));
      k += 3;
      if (k < tokens.size() && legacy_keyword(tokens[k].text) == "OFFSETS") {  // version 5.1: n offsets, size connectivity
        k += 2;
        require(n, true, std::string(key) + " OFFSETS", line);
        if (k >= tokens.size() || legacy_keyword(tokens[k].text) != "CONNECTIVITY")
          throw InputError(locate(path, line, -1, std::string(key) + ": OFFSETS is not followed by CONNECTIVITY"));
        k += 2;
        require(size, true, std::string(key) + " CONNECTIVITY", line);
      } else {
        require(size, true, std::string(key), line);
      }
    } else if (key == "FIELD") {
      // FIELD NAME n, then n arrays NAME components tuples TYPE of components x tuples values (a bad array
      // header crashed VTK 9.1's legacy reader too; found by the vtk fuzz harness).
      const double arrays = count_at(k + 2);
      if (arrays < 0) throw InputError(locate(path, line, -1, "FIELD needs a name and a count of arrays"));
      k += 3;
      static const char* const kLegacyTypes[] = {"bit",  "unsigned_char", "char",   "unsigned_short", "short",
                                                 "unsigned_int", "int", "unsigned_long", "long", "float",
                                                 "double", "vtkIdType", "vtktypeint64", "vtktypeuint64"};
      for (double a = 0; a < arrays; ++a) {
        if (k + 3 >= tokens.size())
          throw InputError(locate(path, line, -1, "FIELD ends before its " + number_text(arrays) + " arrays"));
        const long at_line = tokens[k].line;
        const double components = count_at(k + 1), tuples = count_at(k + 2);
        const std::string_view type = tokens[k + 3].text;
        bool known = false;
        for (const char* t : kLegacyTypes) known = known || type == t;
        if (components < 0 || tuples < 0 || !known)
          throw InputError(locate(path, at_line, -1, "FIELD (line " + std::to_string(line) + "): the array '" +
                                                         excerpt(tokens[k].text) +
                                                         "' needs NAME COMPONENTS TUPLES TYPE with a numeric type"));
        k += 4;
        require(components * tuples, false, "FIELD array", at_line);
      }
    } else if (key == "CELL_DATA" || key == "POINT_DATA") {
      return;  // the attributes after the geometry: VTK's own checks (no crash found there)
    } else {
      ++k;
    }
  }
}

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
const std::pair<const char*, int> kCellFields[] = {{"rho", 3},         {"E", 3},        {"side", 1},
                                                   {"material_id", 1}, {"group_id", 1}, {"object_id", 1}};
const char* const kTables[] = {"material_names", "group_names", "object_names"};

// --- legacy .vtk: VTK's reader ---------------------------------------------------------------------------------

vtkSmartPointer<vtkPolyData> parse_legacy(const std::string& path, std::string_view bytes) {
  CaptureScope capture;
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw InputError(locate(path, 0, -1, "a legacy .vtk file above 2 GiB is not read (write it as .vtp)"));
  vtkNew<vtkPolyDataReader> reader;
  reader->ReadFromInputStringOn();
  reader->SetBinaryInputString(bytes.data(), static_cast<int>(bytes.size()));
  reader->Update();
  vtkSmartPointer<vtkPolyData> out = reader->GetOutput();
  if (!capture.error().empty())
    throw InputError(locate(path, 0, -1, "VTK cannot read it: " + excerpt(capture.error())));
  if (!out) throw InputError(locate(path, 0, -1, "VTK read no polygonal data"));
  return out;
}

SurfaceData legacy_surface(const std::string& path, std::string_view bytes) {
  check_declared_counts(path, bytes);
  check_ascii_legacy_sections(path, bytes);
  const vtkSmartPointer<vtkPolyData> data = parse_legacy(path, bytes);
  SurfaceData s;
  const vtkIdType n_points = data->GetNumberOfPoints();
  if (n_points > std::numeric_limits<std::int32_t>::max() / 2)
    throw InputError(locate(path, 0, -1, "too many points"));
  s.points.resize(static_cast<std::size_t>(n_points));
  for (vtkIdType k = 0; k < n_points; ++k) {
    double p[3];
    data->GetPoint(k, p);
    s.points[static_cast<std::size_t>(k)] = Vec3(p[0], p[1], p[2]);
  }
  const vtkIdType n_verts = data->GetNumberOfVerts(), n_lines = data->GetNumberOfLines();
  const vtkIdType n_polys = data->GetNumberOfPolys(), n_strips = data->GetNumberOfStrips();
  s.cells = static_cast<std::size_t>(n_verts + n_lines + n_polys + n_strips);
  s.ignored = static_cast<std::size_t>(n_verts + n_lines);
  vtkNew<vtkIdList> ids;
  std::size_t cell = s.ignored;
  long face = 0;
  for (const bool strip : {false, true}) {
    vtkCellArray* cells = strip ? data->GetStrips() : data->GetPolys();
    const vtkIdType n = strip ? n_strips : n_polys;
    for (vtkIdType c = 0; c < n; ++c, ++cell) {
      cells->GetCellAtId(c, ids);
      if (!strip && static_cast<std::size_t>(ids->GetNumberOfIds()) > kMaxPolygonCorners)
        throw InputError(locate(path, 0, face, "polygon of " + std::to_string(ids->GetNumberOfIds()) +
                                                   " corners, more than " + std::to_string(kMaxPolygonCorners)));
      const std::size_t begin = s.ids.size();
      for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k) {
        const vtkIdType id = ids->GetId(k);
        if (id < 0 || id >= n_points)
          throw InputError(locate(path, 0, face, "point id " + std::to_string(id) + " is out of range (" +
                                                     std::to_string(n_points) + " points)"));
        s.ids.push_back(static_cast<std::int32_t>(id));
      }
      face += strip ? std::max<long>(0, static_cast<long>(s.ids.size() - begin) - 2) : 1;
      s.surface.push_back({cell, strip, begin, s.ids.size()});
    }
  }
  for (const auto& [name, components] : kCellFields) {
    vtkDataArray* a = data->GetCellData()->GetArray(name);
    if (!a || a->GetNumberOfComponents() != components || static_cast<std::size_t>(a->GetNumberOfTuples()) != s.cells)
      continue;
    std::vector<double>& values = s.cell_data[name];
    for (vtkIdType t = 0; t < a->GetNumberOfTuples(); ++t)
      for (int c = 0; c < components; ++c) values.push_back(a->GetComponent(t, c));
  }
  for (const char* name : kTables) {
    auto* a = vtkStringArray::SafeDownCast(data->GetFieldData()->GetAbstractArray(name));
    if (!a) continue;
    std::vector<std::string>& table = s.tables[name];
    for (vtkIdType k = 0; k < a->GetNumberOfValues(); ++k) table.push_back(a->GetValue(k));
  }
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

  PolygonFaces faces(mesh, options.strict);
  std::int32_t face = 0;
  auto add_cell = [&](std::size_t cell, const std::vector<std::int32_t>& point_ids) {
    const std::int32_t source = face++;
    if (side && (*side)[cell] == 1) {  // a back cell: its front stands for it
      mesh.materials[static_cast<std::size_t>(material_for(cell))].two_sided = true;
      return;
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
  return mesh;
}

}  // namespace radwalk
