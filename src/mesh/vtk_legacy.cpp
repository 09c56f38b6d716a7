#include "mesh/vtk_legacy.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <set>

#include "core/error.h"
#include "core/excerpt.h"
#include "mesh/text_scan.h"
#include "mesh/vtk_legacy_array.h"
#include "mesh/vtk_legacy_scan.h"

namespace radwalk {
namespace {

using Token = LegacyScanner::Token;

constexpr std::int64_t kMostPoints = std::numeric_limits<std::int32_t>::max() / 2;
constexpr std::int64_t kMostId = std::numeric_limits<std::int32_t>::max();

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

// "KEY (line L)" for a header read before any binary data, else "KEY": how a section is named in messages about
// its values.
std::string section_label(const std::string& key, const Token& header) {
  return header.before_raw ? key + " (line " + std::to_string(header.line) + ")" : key;
}

// The major version of "# vtk DataFile Version M.m" as VTK reads it (sscanf "%d.%d" after the prefix: both numbers
// or the version is 0).
int major_version(std::string_view rest) {
  std::size_t i = 0;
  auto number = [&](long& out) {
    while (i < rest.size() && (rest[i] == ' ' || rest[i] == '\t')) ++i;
    const std::size_t start = i;
    if (i < rest.size() && (rest[i] == '+' || rest[i] == '-')) ++i;
    const std::size_t digits = i;
    while (i < rest.size() && std::isdigit(static_cast<unsigned char>(rest[i])) && i - digits < 9) ++i;
    if (i == digits) return false;
    out = std::stol(std::string(rest.substr(start, i - start)));
    return true;
  };
  long major = 0, minor = 0;
  if (!number(major) || i >= rest.size() || rest[i] != '.') return 0;
  ++i;
  if (!number(minor)) return 0;
  return static_cast<int>(std::clamp<long>(major, -1000, 1000));
}

class Reader {
 public:
  Reader(const std::string& path, std::string_view bytes, const LegacyWanted& wanted)
      : scan_(path, bytes), wanted_(wanted) {}

  LegacyPolyData read() {
    header();
    geometry();
    check_point_ids();
    return std::move(out_);
  }

 private:
  void header() {
    const std::string_view prefix = "# vtk DataFile Version";
    const std::string_view first = scan_.rest_of_line();
    if (first.substr(0, prefix.size()) != prefix)
      throw InputError(locate(scan_.path(), 1, -1, "not a legacy VTK file: the first line '" + excerpt(first) +
                                                       "' is not '# vtk DataFile Version M.m'"));
    major_ = major_version(first.substr(prefix.size()));
    if (scan_.at_end()) throw InputError(locate(scan_.path(), 1, -1, "the file ends before its title line"));
    scan_.rest_of_line();  // the title
    const Token encoding = scan_.require("ASCII or BINARY (line 3)");
    const std::string e = lower(encoding.text);
    if (e != "ascii" && e != "binary")
      scan_.refuse(encoding, "'" + excerpt(encoding.text) + "' where ASCII or BINARY belongs");
    binary_ = e == "binary";
    const Token dataset = scan_.require("DATASET POLYDATA");
    if (lower(dataset.text) != "dataset") {
      const std::string d = lower(dataset.text);
      if (d == "cell_data" || d == "point_data")
        scan_.refuse(dataset, upper(d) + " without geometry: no DATASET POLYDATA before it");
      scan_.refuse(dataset, "'" + excerpt(dataset.text) + "' where DATASET POLYDATA belongs");
    }
    const Token kind = scan_.require("the DATASET's type");
    if (lower(kind.text) != "polydata")
      scan_.refuse(kind, "DATASET " + excerpt(kind.text) +
                             ": radwalk reads legacy POLYDATA only (write the surface as POLYDATA, or as .vtp)");
  }

  // The sections of DATASET POLYDATA up to the first CELL_DATA or POINT_DATA, then the attribute sections.
  void geometry() {
    while (const std::optional<Token> t = scan_.next()) {
      const std::string key = upper(t->text);
      if (key == "FIELD") {
        field(*t, false, 0, true);
      } else if (key == "POINTS") {
        points(*t);
      } else if (key == "VERTICES" || key == "LINES" || key == "POLYGONS" || key == "TRIANGLE_STRIPS") {
        LegacyCells& c = key == "VERTICES" ? out_.verts : key == "LINES" ? out_.lines : key == "POLYGONS" ? out_.polys
                                                                                                          : out_.strips;
        once(key, *t);
        cells(*t, key, c);
      } else if (key == "CELL_DATA" || key == "POINT_DATA") {
        attributes(*t);
        return;
      } else {
        scan_.refuse(*t, "'" + excerpt(t->text) +
                             "' is not a POLYDATA section (FIELD, POINTS, VERTICES, LINES, POLYGONS, TRIANGLE_STRIPS, "
                             "CELL_DATA, POINT_DATA)");
      }
    }
  }

  // A section that may come once.
  void once(const std::string& key, const Token& t) {
    const auto [it, added] = seen_.emplace(key, t.before_raw ? t.line : 0);
    if (!added)
      scan_.refuse(t, key + " given twice" +
                          (it->second > 0 ? " (first on line " + std::to_string(it->second) + ")" : std::string()));
  }

  void points(const Token& header) {
    once("POINTS", header);
    const std::string label = section_label("POINTS", header);
    const std::int64_t n = count(header, "POINTS", "points", 3);
    const Token type = scan_.require("the POINTS type");
    if (!is_legacy_type(type.text) || lower(type.text) == "string" || lower(type.text) == "utf8_string" ||
        lower(type.text) == "variant")
      scan_.refuse(type, "POINTS of type '" + excerpt(type.text) +
                             "': not one of VTK's numeric types (float, double, int, ...)");
    const LegacyArray a = read_legacy_array(scan_, type, n, 3, binary_, true, label);
    out_.points.resize(static_cast<std::size_t>(n));
    for (std::size_t k = 0; k < out_.points.size(); ++k) {
      out_.points[k] = Vec3(a.numbers[3 * k], a.numbers[3 * k + 1], a.numbers[3 * k + 2]);
      if (!out_.points[k].allFinite())
        scan_.refuse(header, "POINTS: point " + std::to_string(k) + " is not finite (" +
                                 number_text(out_.points[k].x()) + ", " + number_text(out_.points[k].y()) + ", " +
                                 number_text(out_.points[k].z()) + ")");
    }
  }

  // The count after a section's header: a whole number >= 0 whose items, at `per_item` bytes each at least, fit
  // the bytes left (a loose bound before anything is sized by it; the readers of the values check exactly), and
  // for POINTS at most kMostPoints.
  std::int64_t count(const Token& header, const std::string& key, const std::string& items, int per_item) {
    const Token t = scan_.require("the count after " + key);
    const std::optional<long> n = parse_long(t.text);
    if (!n || *n < 0) scan_.refuse(t, key + ": '" + excerpt(t.text) + "' is not a count (a whole number >= 0)");
    if (static_cast<double>(*n) * per_item > static_cast<double>(scan_.left()))
      scan_.refuse(header, key + " declares " + std::to_string(*n) + " " + items + ", more than its remaining " +
                               std::to_string(scan_.left()) + " bytes can hold (truncated file or wrong count)");
    if (key == "POINTS" && *n > kMostPoints)
      scan_.refuse(header, "POINTS declares " + std::to_string(*n) + " points, more than radwalk reads (" +
                               std::to_string(kMostPoints) + ")");
    return *n;
  }

  void cells(const Token& header, const std::string& key, LegacyCells& c) {
    const std::string label = section_label(key, header);
    if (major_ >= 5) {
      const std::int64_t offsets = count(header, key, "offsets", 1);
      const std::int64_t size = count(header, key, "point ids", 1);
      if (offsets < 1) {
        c.offsets.assign(1, 0);  // no cells (VTK reads no arrays then)
        return;
      }
      const LegacyArray o = cell_array(header, key, "OFFSETS", offsets);
      const LegacyArray ids = cell_array(header, key, "CONNECTIVITY", size);
      if (o.numbers.front() != 0)
        scan_.refuse(header, key + " OFFSETS: the first offset is " + number_text(o.numbers.front()) + ", not 0");
      for (std::size_t k = 1; k < o.numbers.size(); ++k)
        if (!(o.numbers[k] >= o.numbers[k - 1] && o.numbers[k] <= static_cast<double>(size)))
          scan_.refuse(header, key + " OFFSETS: offset " + number_text(o.numbers[k]) + " of cell " +
                                   std::to_string(k - 1) + " is not between the previous offset " +
                                   number_text(o.numbers[k - 1]) + " and the connectivity's " + std::to_string(size) +
                                   " ids");
      if (o.numbers.back() != static_cast<double>(size))
        scan_.refuse(header, key + " OFFSETS end at " + number_text(o.numbers.back()) + ", not at the connectivity's " +
                                 std::to_string(size) + " ids");
      c.offsets.assign(o.numbers.begin(), o.numbers.end());
      c.ids.reserve(ids.numbers.size());
      for (const double id : ids.numbers) {
        if (!(id >= 0 && id <= static_cast<double>(kMostId)))
          scan_.refuse(header, key + " CONNECTIVITY: point id " + number_text(id) + " is not from 0 to " +
                                   std::to_string(kMostId));
        c.ids.push_back(static_cast<std::int32_t>(id));
      }
      return;
    }
    // The classic layout: n cells in `size` whole numbers, each cell its count then its ids.
    const std::int64_t n = count(header, key, "cells", 1);
    const std::int64_t size = count(header, key, "indices", binary_ ? 4 : 1);
    std::vector<std::int32_t> values;
    values.reserve(static_cast<std::size_t>(size));
    if (binary_) {
      if (size > 0) {
        scan_.rest_of_line();
        const std::string_view block = scan_.raw(static_cast<std::size_t>(size) * 4, label);
        for (std::int64_t k = 0; k < size; ++k) {
          const char* p = block.data() + 4 * k;
          const std::uint32_t w = (std::uint32_t{static_cast<unsigned char>(p[0])} << 24) |
                                  (std::uint32_t{static_cast<unsigned char>(p[1])} << 16) |
                                  (std::uint32_t{static_cast<unsigned char>(p[2])} << 8) |
                                  std::uint32_t{static_cast<unsigned char>(p[3])};
          if (w > static_cast<std::uint32_t>(kMostId))
            scan_.refuse_here(label + ": value " + std::to_string(k) + " (" +
                              std::to_string(static_cast<std::int32_t>(w)) + ") is not from 0 to " +
                              std::to_string(kMostId));
          values.push_back(static_cast<std::int32_t>(w));
        }
      }
    } else {
      for (std::int64_t k = 0; k < size; ++k) {
        const std::optional<Token> v = scan_.next();
        if (!v)
          scan_.refuse(header, key + " ends before its " + std::to_string(size) + " indices");
        const std::optional<long> w = parse_long(v->text);
        if (!w || *w < 0 || *w > kMostId)
          scan_.refuse(*v, label + ": '" + excerpt(v->text) + "' is not a whole number from 0 to " +
                               std::to_string(kMostId));
        values.push_back(static_cast<std::int32_t>(*w));
      }
    }
    c.offsets.assign(1, 0);
    std::size_t at = 0;
    while (at < values.size()) {
      const auto corners = static_cast<std::size_t>(values[at]);
      if (corners > values.size() - at - 1)
        scan_.refuse(header, key + ": cell " + std::to_string(c.count()) + " of " + std::to_string(corners) +
                                 " points runs past the section's " + std::to_string(size) + " indices");
      c.ids.insert(c.ids.end(), values.begin() + static_cast<std::ptrdiff_t>(at + 1),
                   values.begin() + static_cast<std::ptrdiff_t>(at + 1 + corners));
      c.offsets.push_back(static_cast<std::int64_t>(c.ids.size()));
      at += 1 + corners;
    }
    if (static_cast<std::int64_t>(c.count()) != n)
      scan_.refuse(header, key + " declares " + std::to_string(n) + " cells, but its " + std::to_string(size) +
                               " indices hold " + std::to_string(c.count()));
  }

  // The OFFSETS or CONNECTIVITY array of a version 5 cell section: `n` whole numbers.
  LegacyArray cell_array(const Token& header, const std::string& key, const std::string& which, std::int64_t n) {
    const Token word = scan_.require(key + "'s " + which);
    if (upper(word.text) != which)
      scan_.refuse(word, key + ": '" + excerpt(word.text) + "' where " + which +
                             " belongs (a version 5 file's cells are OFFSETS and CONNECTIVITY arrays)");
    const Token type = scan_.require(key + "'s " + which + " type");
    LegacyArray a = read_legacy_array(scan_, type, n, 1, binary_, true, section_label(key, header) + " " + which);
    if (!a.integer)
      scan_.refuse(type, key + " " + which + " of type " + a.type + ": cell arrays hold whole numbers");
    return a;
  }

  // CELL_DATA and POINT_DATA sections (one may follow the other) up to the end of the file.
  void attributes(Token section) {
    for (;;) {
      const bool cell = upper(section.text) == "CELL_DATA";
      const std::size_t expected = cell ? out_.verts.count() + out_.lines.count() + out_.polys.count() +
                                              out_.strips.count()
                                        : out_.points.size();
      const Token n_token = scan_.require("the count after " + upper(section.text));
      const std::optional<long> n = parse_long(n_token.text);
      if (!n || *n < 0 || static_cast<std::size_t>(*n) != expected)
        scan_.refuse(n_token, upper(section.text) + " " + excerpt(n_token.text) + ": the file has " +
                                  std::to_string(expected) + (cell ? " cells" : " points"));
      const auto tuples = static_cast<std::int64_t>(expected);
      std::optional<Token> next;
      while ((next = scan_.next())) {
        const std::string key = upper(next->text);
        if (key == "CELL_DATA" || key == "POINT_DATA") break;
        attribute(*next, key, cell, tuples);
      }
      if (!next) return;
      section = *next;
    }
  }

  // One attribute of a CELL_DATA (cell) or POINT_DATA section of `tuples` tuples.
  void attribute(const Token& header, const std::string& key, bool cell, std::int64_t tuples) {
    const std::string where = cell ? "CELL_DATA" : "POINT_DATA";
    if (key == "FIELD") return field(header, cell, tuples, false);
    const bool known = key == "SCALARS" || key == "COLOR_SCALARS" || key == "LOOKUP_TABLE" || key == "VECTORS" ||
                       key == "NORMALS" || key == "TENSORS" || key == "TENSORS6" || key == "TEXTURE_COORDINATES" ||
                       key == "GLOBAL_IDS" || key == "PEDIGREE_IDS" || (key == "EDGE_FLAGS" && !cell);
    if (!known)
      scan_.refuse(header, "'" + excerpt(header.text) + "' is not a " + where +
                               " attribute (SCALARS, COLOR_SCALARS, LOOKUP_TABLE, VECTORS, NORMALS, TENSORS, "
                               "TEXTURE_COORDINATES, GLOBAL_IDS, PEDIGREE_IDS, " +
                               (cell ? "" : "EDGE_FLAGS, ") + "FIELD)");
    const Token name_token = scan_.require(key + "'s name");
    const std::string name = decode_legacy_string(name_token.text);
    const std::string label = section_label(key + " '" + excerpt(name) + "'", header);
    if (key == "LOOKUP_TABLE") {  // NAME n, then n RGBA colours (ASCII: numbers; BINARY: bytes)
      const Token size_token = scan_.peek().value_or(header);
      const std::int64_t size = read_legacy_count(scan_, label + " size", 0, kMostId);
      const Token type{binary_ ? "unsigned_char" : "float", size_token.line, size_token.byte};
      read_legacy_array(scan_, type, size, 4, binary_, false, label);
      return;
    }
    if (key == "COLOR_SCALARS") {  // NAME k: ASCII floats stored as bytes round(255 v), BINARY bytes
      const Token k_token = scan_.peek().value_or(header);
      const std::int64_t k = read_legacy_count(scan_, label + " components", 1, kMostId);
      const Token type{binary_ ? "unsigned_char" : "float", k_token.line, k_token.byte};
      const bool keep = kept(cell, name, k);
      LegacyArray a = read_legacy_array(scan_, type, tuples, k, binary_, keep, label);
      if (!binary_)
        for (double& v : a.numbers) v = std::floor(std::clamp(255.0 * v + 0.5, 0.0, 255.0));
      if (keep) keep_cell_array(header, name, std::move(a));
      return;
    }
    std::int64_t components = 1;
    Token type{};
    if (key == "TEXTURE_COORDINATES") {
      components = read_legacy_count(scan_, label + " dimension", 1, 3);
      type = scan_.require(label + "'s type");
    } else {
      type = scan_.require(label + "'s type");
      if (key == "VECTORS" || key == "NORMALS") components = 3;
      if (key == "TENSORS") components = 9;
      if (key == "TENSORS6") components = 6;
    }
    if (key == "SCALARS") {  // NAME TYPE [k] LOOKUP_TABLE T
      Token word = scan_.require(label + "'s LOOKUP_TABLE");
      if (upper(word.text) != "LOOKUP_TABLE") {
        const std::optional<long> k = parse_long(word.text);
        if (!k || *k < 1 || *k > kMostId)
          scan_.refuse(word, label + ": '" + excerpt(word.text) + "' is neither a component count nor LOOKUP_TABLE");
        components = *k;
        word = scan_.require(label + "'s LOOKUP_TABLE");
      }
      if (upper(word.text) != "LOOKUP_TABLE")
        scan_.refuse(word, label + ": '" + excerpt(word.text) +
                               "' where LOOKUP_TABLE belongs (\"LOOKUP_TABLE default\" for none)");
      scan_.require(label + "'s lookup table name");
    }
    const bool keep = kept(cell, name, components);
    LegacyArray a = read_legacy_array(scan_, type, tuples, components, binary_, keep, label);
    if (keep && a.numeric) keep_cell_array(header, name, std::move(a));
  }

  // Whether a cell data array of this name and component count is one the caller uses.
  bool kept(bool cell, const std::string& name, std::int64_t components) const {
    if (!cell) return false;
    const auto it = wanted_.cell_arrays.find(name);
    return it != wanted_.cell_arrays.end() && it->second == components;
  }

  void keep_cell_array(const Token& header, const std::string& name, LegacyArray a) {
    if (!a.numeric) return;
    if (!out_.cell_data.emplace(name, std::move(a.numbers)).second)
      scan_.refuse(header, "cell data '" + excerpt(name) + "' given twice: which one is meant?");
  }

  // FIELD NAME n: n arrays, each NAME k tuples TYPE and its values, or NULL_ARRAY. In a CELL_DATA section (cell)
  // its arrays of `tuples` tuples are cell data; at the data set's level its string arrays are tables.
  void field(const Token& header, bool cell, std::int64_t tuples, bool data_set_level) {
    scan_.require("FIELD's name");
    const std::string label = section_label("FIELD", header);
    const std::int64_t arrays = read_legacy_count(scan_, label + " array count", 0, kMostId);
    if (static_cast<double>(arrays) > static_cast<double>(scan_.left()))
      scan_.refuse(header, label + " declares " + std::to_string(arrays) + " arrays, more than its remaining " +
                               std::to_string(scan_.left()) + " bytes can hold");
    for (std::int64_t i = 0; i < arrays; ++i) {
      const Token array_name = scan_.require(label + "'s array " + std::to_string(i));
      if (array_name.text == "NULL_ARRAY") continue;
      const std::string decoded = decode_legacy_string(array_name.text);
      const std::string what = section_label("FIELD array '" + excerpt(decoded) + "'", array_name);
      const std::int64_t components = read_legacy_count(scan_, what + " components", 0, kMostId);
      const std::int64_t n = read_legacy_count(scan_, what + " tuples", 0, std::numeric_limits<long>::max());
      const Token type = scan_.require(what + "'s type");
      const bool table = data_set_level && std::find(wanted_.field_strings.begin(), wanted_.field_strings.end(),
                                                     decoded) != wanted_.field_strings.end();
      const bool keep_numbers = cell && n == tuples && kept(cell, decoded, components);
      LegacyArray a = read_legacy_array(scan_, type, n, components, binary_, table || keep_numbers, what);
      if (table && !a.numeric && a.type != "variant" &&
          !out_.field_strings.emplace(decoded, std::move(a.strings)).second)
        scan_.refuse(array_name, "field data '" + excerpt(decoded) + "' given twice: which one is meant?");
      if (keep_numbers) keep_cell_array(array_name, decoded, std::move(a));
    }
  }

  // Every point id of every cell below the points (the cells may come before POINTS).
  void check_point_ids() {
    const std::size_t n = out_.points.size();
    const std::pair<const char*, const LegacyCells*> kinds[] = {
        {"VERTICES", &out_.verts}, {"LINES", &out_.lines}, {"POLYGONS", &out_.polys}, {"TRIANGLE_STRIPS", &out_.strips}};
    for (const auto& [key, c] : kinds) {
      for (std::size_t cell = 0; cell < c->count(); ++cell)
        for (auto k = c->offsets[cell]; k < c->offsets[cell + 1]; ++k) {
          const std::int32_t id = c->ids[static_cast<std::size_t>(k)];
          if (static_cast<std::size_t>(id) >= n) {
            const auto line = seen_.find(key)->second;
            throw InputError(locate(scan_.path(), line, -1,
                                    std::string(key) + ": cell " + std::to_string(cell) + ": point id " +
                                        std::to_string(id) + " is out of range (" + std::to_string(n) + " points)"));
          }
        }
    }
  }

  LegacyScanner scan_;
  const LegacyWanted& wanted_;
  LegacyPolyData out_;
  int major_ = 0;
  bool binary_ = false;
  std::map<std::string, long> seen_;  // sections given once, with their lines (0: after binary data)
};

}  // namespace

LegacyPolyData parse_vtk_legacy(const std::string& path, std::string_view bytes, const LegacyWanted& wanted) {
  return Reader(path, bytes, wanted).read();
}

}  // namespace radwalk
